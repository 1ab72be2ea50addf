#pragma once
// Which frames `spume compare REFERENCE NEW` compares. Each side is a PNG file, a folder (its *.png
// files, matched by name; a folder without PNGs but with a frames/ subfolder, such as a scene's
// output folder, means that subfolder) or a frame pattern such as out/wave/frames/%04d.png (frames
// matched by number). A pattern on one side and a folder on the other applies the pattern's file
// name inside the folder. Frames are listed whether present on both sides or one.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "render/app/cli/cli_args.h"

namespace spume::compare {

// Something the user typed cannot be run (arguments, options, paths): exit status 2, not 1.
using UsageError = cli::UsageError;

struct FramePair {
  std::string label;          // file name as reports show it ("0012.png"); unique in a FrameSet
  std::string stem;           // file-name-safe and unique: names this frame's output images
  std::optional<int> number;  // frame number (patterns: the placeholder; folders: the name's last digits)
  std::filesystem::path reference, candidate;  // where the frame is, or would be when missing
  bool has_reference = false, has_candidate = false;
};

struct FrameSet {
  enum class Mode { files, folders, patterns } mode = Mode::files;
  std::string reference_source, candidate_source;  // the file, folder or pattern each side resolved to
  std::vector<FramePair> frames;                   // by number, else by name with digit runs compared as numbers
  std::vector<std::string> notes;  // how an argument was read, when not as typed; "warning: ..." lines
};

// `frames_spec` (the frame-spec grammar) selects numbered frames. With patterns, a selected frame in
// the range found on either side that neither side has is listed as missing on both. Throws
// UsageError for a path that does not exist, a file against a folder or pattern, a malformed pattern
// or spec, --frames with two files, or no PNG on either side.
FrameSet resolve_frames(const std::string& reference, const std::string& candidate,
                        const std::optional<std::string>& frames_spec);

// Orders "frame_2.png" before "frame_10.png": digit runs compare as numbers, the rest byte by byte.
bool natural_less(const std::string& a, const std::string& b);

}  // namespace spume::compare
