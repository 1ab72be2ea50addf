#include "render/keys/key_catalog.h"

#include <algorithm>

#include "sim/keys/diffuse_keys.h"
#include "render/keys/render_keys.h"
#include "sim/keys/scene_keys.h"

namespace spume {
namespace {

std::string type_text(const KeySpec& k) {
  switch (k.type) {
    case KeyType::Number: return "number";
    case KeyType::Integer: return "whole number";
    case KeyType::Boolean: return "true|false";
    case KeyType::Text: return "string";
    case KeyType::Choice: return "choice";
    case KeyType::Vec3: return "[x, y, z]";
    case KeyType::Colour: return "[r, g, b]";
    case KeyType::Range: return "[min, max]";
    case KeyType::Size: return "[width, height]";
    case KeyType::Object: return "{...}";
    case KeyType::List: return "[{...}, ...]";
  }
  return "";
}

// Pipes inside cells would break a markdown table.
std::string cell(std::string text) {
  for (size_t at = text.find('|'); at != std::string::npos; at = text.find('|', at + 2)) text.replace(at, 1, "\\|");
  return text;
}

}  // namespace

const std::vector<KeyGroup>& key_groups() {
  static const std::vector<KeyGroup> groups = {
      {"scene", keys::scene::all},     {"fluid", keys::fluid::all},   {"solver", keys::solver::all},
      {"solids", keys::solids::all},   {"domain", keys::domain::all}, {"output", keys::output::all},
      {"diffuse", keys::diffuse::all}, {"render", keys::render::all},
  };
  return groups;
}

std::string key_table_markdown(const KeyGroup& group) {
  std::string out = "| key | type | unit | default | allowed | meaning |\n|---|---|---|---|---|---|\n";
  for (const KeySpec* k : group.keys)
    out += "| `" + std::string(k->path) + "` | " + cell(type_text(*k)) + " | " + cell(k->unit) + " | " +
           cell(default_description(*k)) + " | " + cell(range_description(*k)) + " | " + cell(k->doc) + " |\n";
  return out;
}

std::string key_listing(const std::string& prefix) {
  std::vector<const KeySpec*> chosen;
  for (const KeyGroup& g : key_groups())
    for (const KeySpec* k : g.keys)
      if (std::string(k->path).rfind(prefix, 0) == 0) chosen.push_back(k);
  size_t width = 0;
  for (const KeySpec* k : chosen) width = std::max(width, std::string(k->path).size());
  std::string out;
  for (const KeySpec* k : chosen) {
    std::string line = k->path;
    line.resize(width + 2, ' ');
    line += k->doc;
    out += line + "\n";
    std::string detail = std::string(width + 2, ' ') + type_text(*k);
    if (*k->unit) detail += ", " + std::string(k->unit);
    if (const std::string d = default_description(*k); !d.empty()) detail += "; default " + d;
    if (const std::string r = range_description(*k); !r.empty()) detail += "; allowed " + r;
    out += detail + "\n";
  }
  return out;
}

}  // namespace spume
