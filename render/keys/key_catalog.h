#pragma once
// Every declared key, by group, for people: `spume keys [PREFIX]` prints them, and the key tables
// of sim/keys/KEYS.md are these tables (tests/render/key_tables_test.cpp compares the two).
#include <span>
#include <string>
#include <vector>

#include "sim/keys/key_spec.h"

namespace spume {

struct KeyGroup {
  const char* name;  // "diffuse": sim/keys/KEYS.md marks its table <!-- keys: diffuse -->
  std::span<const KeySpec* const> keys;
};

// scene, fluid, solver, solids, domain, output, diffuse, render.
const std::vector<KeyGroup>& key_groups();

// A markdown table: | key | unit | default | allowed | meaning |.
std::string key_table_markdown(const KeyGroup& group);

// Plain text, aligned, for a terminal: the keys whose path starts with `prefix` ("" for all).
std::string key_listing(const std::string& prefix);

}  // namespace spume
