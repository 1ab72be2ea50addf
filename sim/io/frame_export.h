#pragma once
// Exports: per-frame copies of a stage's caches in other tools' formats (BGEO, OpenVDB points), made
// from the caches after the stage ran, each kind in a folder of its own with a record of its own
// (io/stage_record.h):
//   OUT/<scene>/<folder>/<prefix>_0000<extension>   one per frame the stage's caches hold
//   OUT/<scene>/<folder>/record.json                the format, and the cache each file was made from
// A folder belongs to the run that made the caches: it holds exactly the frames of the stage's
// record, each made from that frame's cache as it is now. A frame is written again only when its
// cache (size and modification time) or the format changed; a file of any other frame (an earlier
// run's, over another range or other keys) is removed, and so is everything when the export is off.
// The log says what was written or removed and why. The record goes first and comes back last, so an
// interrupted export is never taken for a finished one. Turning an export on or off re-simulates
// nothing: the stages' keys leave the output.* keys out (scene/sim_scene.cpp).
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace spume {

struct FrameExport {
  std::string folder;      // "diffuse_vdb"
  std::string key;         // "output.vdb": the key that asks for it, for the log
  std::string prefix;      // "diffuse": files are <prefix>_<frame, 4 digits or more><extension>
  std::string extension;   // ".vdb"
  bool on = false;
  nlohmann::json format = nlohmann::json::object();  // what the files depend on besides their cache
  std::function<std::filesystem::path(int frame)> cache_of;                  // the cache a frame is made from
  std::function<void(int frame, const std::filesystem::path& file)> write;  // reads it, writes the file
};

struct FrameExportSummary {
  int written = 0, kept = 0, removed = 0;  // files
  double seconds = 0.0;
  std::string why;  // when something was written or removed: why
};

std::filesystem::path export_file_path(const FrameExport& e, const std::filesystem::path& scene_out, int frame);

// Whether bring_export_in_line would write or remove nothing. `frames`: those of the stage's record.
bool export_current(const FrameExport& e, const std::vector<int>& frames, const std::filesystem::path& scene_out);

// Brings OUT/<scene>/<folder>/ in line with the export's key and the caches of `frames`, which must be
// on disk and current (run after the stage). Progress and what it did go to stderr unless quiet.
FrameExportSummary bring_export_in_line(const FrameExport& e, const std::vector<int>& frames,
                                        const std::filesystem::path& scene_out, bool quiet);

}  // namespace spume
