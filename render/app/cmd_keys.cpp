// spume keys: every scene key with its type, unit, default, allowed values and meaning, from the
// declarations themselves (keys/key_spec.h), so a user need not open the README.
#include <cstdio>

#include "commands.h"
#include "core/error.h"
#include "keys/key_catalog.h"

namespace spume {
namespace {

int list_keys(const cli::ParsedArgs& args) {
  if (args.positional.size() > 1) cli::usage_fail("at most one PREFIX");
  if (args.has("markdown")) {
    // The README's tables, between their markers, ready to paste.
    for (const KeyGroup& g : key_groups())
      std::printf("<!-- keys: %s -->\n%s<!-- /keys -->\n\n", g.name, key_table_markdown(g).c_str());
    return 0;
  }
  const std::string prefix = args.positional.empty() ? "" : args.positional[0];
  const std::string listing = key_listing(prefix);
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
  spec.options = {{"markdown", "", "the README's key tables instead, between their <!-- keys: ... --> markers"}};
  spec.runs_without_arguments = true;
  return {spec, list_keys};
}

}  // namespace spume
