// spume info: what a particle file or cache holds.
#include <algorithm>
#include <cctype>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>

#include "render/app/commands.h"
#include "render/app/output_folder_info.h"
#include "render/frame/frame_exr.h"
#include "sim/core/error.h"
#include "sim/core/messages.h"
#include "sim/diffuse/narrow_band.h"
#include "sim/io/vdb_points.h"
#include "sim/io/fluid_import.h"
#include "sim/io/fluid_survey.h"
#include "sim/io/particle_file.h"

namespace spume {
namespace {

namespace fs = std::filesystem;

// "fluid_12.bgeo" -> "fluid_#.bgeo" and 12: the file name with its last run of digits as '#', so the
// frames of one sequence group together.
std::pair<std::string, long> sequence_of(const std::string& name) {
  const size_t end = name.find_last_of("0123456789");
  if (end == std::string::npos) return {name, -1};
  size_t begin = end;
  while (begin > 0 && std::isdigit(static_cast<unsigned char>(name[begin - 1]))) --begin;
  const std::string digits = name.substr(begin, std::min<size_t>(end + 1 - begin, 9));
  return {name.substr(0, begin) + "#" + name.substr(end + 1), std::stol(digits)};
}

// A directory is not a file: say so, and list the particle files in it (as sequences) to choose from.
[[noreturn]] void fail_on_directory(const fs::path& dir) {
  std::map<std::string, std::set<long>> sequences;  // name with '#' -> frame numbers
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
    if (!e.is_regular_file(ec)) continue;
    try {
      particle_format(e.path());
    } catch (const Error&) {
      continue;  // not a particle file
    }
    const auto [sequence, frame] = sequence_of(e.path().filename().string());
    sequences[sequence].insert(frame);
  }
  std::string listing;
  size_t shown = 0;
  for (const auto& [sequence, frames] : sequences) {
    if (++shown > 10) {
      listing += str("\n  ... and ", sequences.size() - 10, " more");
      break;
    }
    listing += frames.size() == 1 || *frames.begin() < 0
                   ? str("\n  ", sequence, frames.size() > 1 ? str(" (", frames.size(), " files)") : "")
                   : str("\n  ", sequence, ": ", frames.size(), " files, numbers ", *frames.begin(), " to ",
                         *frames.rbegin());
  }
  if (sequences.empty())
    fail(dir.string(), ": is a directory, not a particle file, and holds no particle files (",
         "formats: .bgeo .bgeo.gz .bgeo.sc .bhclassic .vtk .vtu .vtp .ply .vdb .spf .spd)");
  fail(dir.string(), ": is a directory, not a particle file; give one of its particle files (# is the frame ",
       "number):", listing);
}

// The radius a run on this file would be told to use: a quarter of the cell of a Mantaflow cache (its
// default 2 particles per cell and axis, the point grid's voxel size), else half the median distance
// to the nearest neighbour (what the run's radius check proposes), with how it was found.
std::pair<float, std::string> implied_radius(const fs::path& path, const FluidImport& import, const FluidFrame& frame) {
  if (import.mantaflow && particle_format(path) == ParticleFormat::Vdb) {
    VdbPointsInfo info;
    read_vdb_points(path, import.read.vdb_grid, &info);
    for (const VdbGridInfo& g : info.grids)
      if (g.used && g.points && g.voxel_size > 0.0)
        return {float(g.voxel_size / 4.0), str("a quarter of Mantaflow's cell, ", g.voxel_size, " m")};
  }
  // To 3 digits, as it is printed and would be given: on a lattice, cells of h = 2 spacings put
  // particles on cell faces, where the last bit of h would move them from cell to cell.
  char digits[32];
  std::snprintf(digits, sizeof digits, "%.3g", 0.5 * double(median_spacing(frame.positions)));
  return {float(std::strtod(digits, nullptr)), "half the median nearest-neighbour distance, to 3 digits"};
}

// Whether a fluid frame is a narrow band (MODEL.md §9.1), by the run's own test: on cells of h = 4 r
// with the radius the file implies, flooded from above (spume's -y gravity, after the up axis "auto"
// decides), a FLIP source as fluid.particles "auto" takes it. "" for files that are not fluid frames.
std::string interior_line(const fs::path& path) {
  const ParticleFormat format = particle_format(path);
  if (format == ParticleFormat::DiffuseCache) return "";
  FluidFrame frame;
  FluidImport import;
  try {
    import = resolve_fluid_import(path, "auto", "", std::nullopt, 0.0);
    frame = read_fluid_file(path, import.read);
  } catch (const Error&) {
    return "";  // spume's diffuse BGEO, or a file describe_particle_file already explained
  }
  if (frame.size() < 2) return "";
  const auto [radius, how] = implied_radius(path, import, frame);
  if (!(radius > 0.0f)) return "";
  InteriorFiller filler;
  const InteriorFill fill = filler.examine(frame.positions, 4.0f * radius, Vec3f(0.0f, -1.0f, 0.0f), import.mantaflow);
  std::string line = "  interior: " + describe_interior(fill);
  if (fill.narrow_band) line += "; a run fills it for the classification and advection (fluid.narrow_band \"auto\")";
  return line + str(" (h = 4 r with r = ", radius, " m, ", how, ", where a run uses its own h, 4 x fluid.radius by "
                    "default; MODEL.md §9.1)\n");
}

int info(const cli::ParsedArgs& args) {
  if (args.positional.empty()) cli::usage_fail("no FILE given");
  for (const auto& path : args.positional) {
    std::error_code ec;
    if (fs::is_directory(path, ec)) {
      const std::optional<OutputFolder> outputs = describe_output_folder(path);
      if (!outputs) fail_on_directory(path);
      std::printf("%s", outputs->description.c_str());
      std::fflush(stdout);
      // On stderr too, so that a script reading only the status and stderr learns it.
      if (outputs->warnings > 0)
        messages::warning(str(path, ": its outputs were made with ", outputs->warnings, " warning",
                              outputs->warnings > 1 ? "s" : "", " (listed above)"));
      continue;
    }
    if (fs::path(path).extension() == ".exr") {  // a rendered frame's layers
      std::printf("%s\n", describe_frame_exr(path).c_str());
      continue;
    }
    std::printf("%s%s\n", describe_particle_file(path).c_str(), interior_line(path).c_str());
  }
  return 0;
}

}  // namespace

Command cmd_info() {
  cli::CommandSpec spec;
  spec.name = "info";
  spec.forms = {"FILE..."};
  spec.summary = "what a particle file or cache holds: format, counts, attributes, bounds";
  spec.notes = {"formats: .bgeo .bgeo.gz .bgeo.sc .bhclassic .vtk .vtu .vtp .ply .vdb, spume caches .spf .spd",
                "a .vdb: its grids, point attributes and codecs, and the up axis and velocity units spume takes",
                "a rendered .exr frame: its layers, how much of the image each covers, Z, motion, provenance",
                "a scene's output folder (OUT/<scene>): its finished caches and the warnings given when they were made",
                "another directory is refused with a list of the particle files in it"};
  spec.options = {cli::quiet_option()};
  spec.max_operands = SIZE_MAX;
  return {spec, info};
}

}  // namespace spume
