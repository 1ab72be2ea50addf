#pragma once
// output.vdb: the diffuse frames as OpenVDB points (io/vdb_points_writer.h), made from the diffuse
// caches after the diffuse stage:
//   OUT/<scene>/diffuse_vdb/diffuse_0000.vdb   one per frame of the diffuse stage's range
//   OUT/<scene>/diffuse_vdb/record.json        the format and voxel, and each .spd it was made from
// The folder has a record of its own (io/stage_record.h): turning the key on or off re-simulates
// nothing. A frame is written again only when its .spd (size and CRC-32) or the format changed; a
// rerun with nothing changed writes nothing. A .vdb of a frame outside the stage's range stays while
// its .spd is unchanged; otherwise it is removed. With output.vdb off, the folder's .vdb files are
// removed with its record. So no .vdb ever disagrees with the .spd beside it. Runs that do not ask
// for .vdb pay one directory check.
#include <filesystem>
#include <string>
#include <vector>

#include "sim/scene/sim_scene.h"

namespace spume {

struct VdbExportSummary {
  int written = 0, kept = 0, removed = 0;  // .vdb files
  double seconds = 0.0;
  std::string why;  // when something was written or removed: why
};

// Whether export_diffuse_vdb would write or remove nothing for these diffuse frames.
bool diffuse_vdb_current(const SimScene& scene, const std::vector<int>& frames, const std::filesystem::path& scene_out);

// Brings OUT/<scene>/diffuse_vdb/ in line with output.vdb and the diffuse caches of `frames`, which
// must be on disk and current (run after the diffuse stage). Progress and what it did go to stderr
// unless quiet.
VdbExportSummary export_diffuse_vdb(const SimScene& scene, const std::vector<int>& frames,
                                    const std::filesystem::path& scene_out, bool quiet);

}  // namespace spume
