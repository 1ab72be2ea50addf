// spume info: what a particle file or cache holds.
#include <cstddef>
#include <cstdio>

#include "commands.h"
#include "core/error.h"
#include "io/particle_file.h"

namespace spume {
namespace {

int info(const cli::ParsedArgs& args) {
  if (args.positional.empty()) cli::usage_fail("no FILE given");
  for (const auto& path : args.positional) std::printf("%s\n", describe_particle_file(path).c_str());
  return 0;
}

}  // namespace

Command cmd_info() {
  cli::CommandSpec spec;
  spec.name = "info";
  spec.forms = {"FILE..."};
  spec.summary = "what a particle file or cache holds: format, counts, attributes, bounds";
  spec.notes = {"formats: .bgeo .bgeo.gz .bhclassic .vtk .vtu .vtp .ply, spume caches .spf .spd"};
  spec.max_operands = SIZE_MAX;
  return {spec, info};
}

}  // namespace spume
