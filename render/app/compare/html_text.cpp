#include "render/app/compare/html_text.h"

#include <cctype>
#include <cstdio>
#include <system_error>

namespace spume::compare {
namespace fs = std::filesystem;

std::string html_escape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string url_path(const std::string& relative) {
  std::string out;
  for (unsigned char c : relative) {
    if (std::isalnum(c) || c == '-' || c == '_' || c == '.' || c == '~' || c == '/') {
      out += char(c);
    } else {
      char buf[4];
      std::snprintf(buf, sizeof buf, "%%%02X", c);
      out += buf;
    }
  }
  return out;
}

std::string relative_url(const fs::path& target, const fs::path& from) {
  std::error_code ec;
  const fs::path abs_target = fs::absolute(target, ec), abs_from = fs::absolute(from, ec);
  fs::path rel = fs::relative(abs_target, abs_from, ec);
  if (ec || rel.empty()) rel = abs_target;  // no relative route (not expected on one file system)
  return url_path(rel.generic_string());
}

}  // namespace spume::compare
