#include "sim/scene/scene_name.h"

#include <algorithm>
#include <cctype>

namespace spume {
namespace {

bool is_name_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.'; }
bool is_edge_trimmed(char c) { return c == '_' || c == '-' || c == '.'; }

}  // namespace

bool is_usable_scene_name(const std::string& name) {
  return !name.empty() && name[0] != '.' && std::all_of(name.begin(), name.end(), is_name_char);
}

std::string usable_scene_name(const std::string& text) {
  std::string name;
  for (char c : text) {
    if (is_name_char(c)) name += c;
    else if (name.empty() || name.back() != '_') name += '_';
  }
  const size_t begin = std::find_if_not(name.begin(), name.end(), is_edge_trimmed) - name.begin();
  size_t end = name.size();
  while (end > begin && is_edge_trimmed(name[end - 1])) --end;
  return name.substr(begin, end - begin);
}

}  // namespace spume
