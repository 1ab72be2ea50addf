// spume info: what a particle file or cache holds.
#include <cstdio>

#include "commands.h"
#include "core/error.h"
#include "io/particle_file.h"

namespace spume {

int command_info(const std::vector<std::string>& args) {
  if (args.empty()) fail("usage: spume info FILE [FILE...]  (.bgeo .vtk .vtu .ply .spf .spd)");
  for (const auto& path : args) std::printf("%s\n", describe_particle_file(path).c_str());
  return 0;
}

}  // namespace spume
