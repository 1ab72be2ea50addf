// spume keys: every scene key with its type, unit, default, allowed values and meaning, from the
// declarations themselves (keys/key_spec.h), so a user need not open sim/keys/KEYS.md.
#include <cstdio>

#include "render/app/commands.h"
#include "sim/core/error.h"
#include "render/keys/key_catalog.h"

namespace spume {
namespace {

// The tables of sim/keys/KEYS.md for the keys under `prefix` ("" for all), ready to paste: a group
// whose every key is chosen keeps its <!-- keys: ... --> markers; a part of a group is a table without
// them, so it cannot be pasted over the whole group's table by mistake. "" when no key starts with it.
std::string markdown_tables(const std::string& prefix) {
  std::string out;
  for (const KeyGroup& g : key_groups()) {
    std::vector<const KeySpec*> chosen;
    for (const KeySpec* k : g.keys)
      if (std::string(k->path).rfind(prefix, 0) == 0) chosen.push_back(k);
    if (chosen.empty()) continue;
    const std::string table = key_table_markdown({g.name, chosen});
    if (chosen.size() == g.keys.size())
      out += str("<!-- keys: ", g.name, " -->\n", table, "<!-- /keys -->\n\n");
    else
      out += table + "\n";
  }
  return out;
}

int list_keys(const cli::ParsedArgs& args) {
  if (args.positional.size() > 1) cli::usage_fail("at most one PREFIX");
  const std::string prefix = args.positional.empty() ? "" : args.positional[0];
  const std::string listing = args.has("markdown") ? markdown_tables(prefix) : key_listing(prefix);
  if (listing.empty()) fail("no key starts with \"", prefix, "\" (try diffuse, render.water, fluid.solver)");
  std::fputs(listing.c_str(), stdout);
  return 0;
}

}  // namespace

Command cmd_keys() {
  cli::CommandSpec spec;
  spec.name = "keys";
  spec.forms = {"[PREFIX] [options]"};
  spec.summary = "every scene key: type, unit, default, allowed values, meaning (e.g. spume keys render.water)";
  spec.options = {{"markdown", "",
                   "as the tables of sim/keys/KEYS.md (a whole group with its <!-- keys --> markers)"}};
  spec.runs_without_arguments = true;
  return {spec, list_keys};
}

}  // namespace spume
