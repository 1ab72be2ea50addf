#include "render/app/compare/threshold_args.h"

#include <cctype>
#include <cmath>
#include <cstdlib>

#include "render/app/compare/frame_set.h"

namespace spume::compare {
namespace {

bool all_digits(const std::string& s) {
  if (s.empty()) return false;
  for (char c : s)
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  return true;
}

}  // namespace

int parse_level(const std::string& text, const std::string& option) {
  std::string digits = text;
  if (digits.size() > 4 && digits.compare(digits.size() - 4, 4, "/255") == 0) digits.resize(digits.size() - 4);
  if (all_digits(digits) && digits.size() <= 3) {
    const int v = std::atoi(digits.c_str());
    if (v <= 255) return v;
  }
  std::string hint;
  char* end = nullptr;
  const double x = std::strtod(text.c_str(), &end);
  if (end && *end == '\0' && !text.empty() && std::isfinite(x) && x > 0 && x < 1)
    hint = str(" (a fraction of full range, as idiff takes it? ", text, " x 255 = ", std::lround(x * 255),
               " level", std::lround(x * 255) == 1 ? "" : "s", ")");
  throw UsageError(str(option, " \"", text, "\": expected a whole number of 8-bit levels from 0 to 255, written N or N/255 "
                       "(1 = 1/255)", hint));
}

DecimalPercent parse_percent(const std::string& text, const std::string& option) {
  std::string s = text;
  if (!s.empty() && s.back() == '%') s.pop_back();
  const size_t dot = s.find('.');
  const std::string whole = s.substr(0, dot), frac = dot == std::string::npos ? "" : s.substr(dot + 1);
  const bool ok = all_digits(whole) && whole.size() <= 3 && (dot == std::string::npos || all_digits(frac)) &&
                  frac.size() <= size_t(DecimalPercent::kMaxDigits);
  if (ok) {
    DecimalPercent p;
    p.digits = int(frac.size());
    p.units = std::strtoull((whole + frac).c_str(), nullptr, 10);
    if (p.value() <= 100.0) return p;
  }
  throw UsageError(str(option, " \"", text, "\": expected a percentage of the frame's pixels from 0 to 100, as a plain "
                       "decimal with at most ", DecimalPercent::kMaxDigits, " decimals (e.g. 0.02 or 0.02%)"));
}

}  // namespace spume::compare
