#include "sim/keys/key_spec.h"

#include <sstream>

namespace spume {
namespace {

std::string number_text(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

// "[a, b]" or "[a, b, c]", written into one stream (GCC 12 warns falsely, -Wrestrict, on "[" + string).
std::string list_text(const KeySpec& k, int n) {
  std::ostringstream out;
  out << "[";
  for (int i = 0; i < n; ++i) out << (i ? ", " : "") << k.value[size_t(i)];
  out << "]";
  return out.str();
}

std::string values_text(const KeySpec& k) {
  switch (k.type) {
    case KeyType::Range:
    case KeyType::Size: return list_text(k, 2);
    case KeyType::Vec3:
    case KeyType::Colour: return list_text(k, 3);
    case KeyType::Boolean: return k.value[0] != 0.0 ? "true" : "false";
    default: return number_text(k.value[0]);
  }
}

}  // namespace

std::string KeySpec::name() const {
  const std::string p = path;
  const size_t dot = p.rfind('.');
  return dot == std::string::npos ? p : p.substr(dot + 1);
}

double scaled_default(const KeySpec& k, int i, double r, double mass_ratio) {
  const double v = k.value[size_t(i)], s = r / kDefaultsReferenceRadius;
  switch (k.scaling) {
    case Scaling::Absolute: return v;
    case Scaling::Radius: return v * r;
    case Scaling::Velocity:
    case Scaling::Time: return v * std::sqrt(s);
    // Rounded as spume always has (1/sqrt(s) and mass_ratio * s first): caches stay byte-identical.
    case Scaling::Rate: return v * (1.0 / std::sqrt(s));
    case Scaling::Energy: return v * (mass_ratio * s);
  }
  return v;
}

std::string default_description(const KeySpec& k) {
  if (k.type == KeyType::Text || k.type == KeyType::Choice) {
    std::string first = k.choices;
    if (k.type == KeyType::Choice) first = first.substr(0, first.find('|'));
    if (!first.empty()) return "\"" + first + "\"";
  }
  if (!k.has_value()) return k.default_text;
  std::string text = values_text(k);
  switch (k.scaling) {
    case Scaling::Absolute: break;
    case Scaling::Radius: text += " r"; break;
    case Scaling::Velocity:
    case Scaling::Time: text += " at r0, x sqrt(r/r0)"; break;
    case Scaling::Rate: text += " at r0, / sqrt(r/r0)"; break;
    case Scaling::Energy: text += " at r0, x mass ratio x r/r0"; break;
  }
  if (*k.default_text) text += std::string(" (") + k.default_text + ")";
  return text;
}

std::string range_description(const KeySpec& k) {
  if (k.type == KeyType::Choice) {
    std::string list = k.choices;
    for (size_t at = list.find('|'); at != std::string::npos; at = list.find('|')) list.replace(at, 1, ", ");
    return list;
  }
  const bool lo = k.lo_bound != Bound::Unset, hi = k.hi_bound != Bound::Unset;
  if (lo && hi)
    return std::string(k.lo_bound == Bound::Open ? "(" : "[") + number_text(k.lo) + ", " + number_text(k.hi) +
           (k.hi_bound == Bound::Open ? ")" : "]");
  if (lo) return std::string(k.lo_bound == Bound::Open ? "> " : ">= ") + number_text(k.lo);
  if (hi) return std::string(k.hi_bound == Bound::Open ? "< " : "<= ") + number_text(k.hi);
  return "";
}

std::string out_of_range(const KeySpec& k, double v) {
  const bool low = k.lo_bound == Bound::Closed ? !(v >= k.lo) : k.lo_bound == Bound::Open && !(v > k.lo);
  const bool high = k.hi_bound == Bound::Closed ? !(v <= k.hi) : k.hi_bound == Bound::Open && !(v < k.hi);
  if (!low && !high && std::isfinite(v)) return "";
  return "value " + number_text(v) + " is out of range; allowed " + range_description(k);
}

}  // namespace spume
