#pragma once
// A frame's layers (frame_layers.h) as one multilayer OpenEXR file, the form compositing tools read:
//   R G B A           beauty, HALF
//   Z                 distance to the first surface, m, FLOAT
//   <layer>.R/G/B/A   sky, opaque, water, then spray, foam, bubble for the drawn types, HALF
//   forward.u/v, backward.u/v   motion vectors, pixels per frame, v up (Nuke's), HALF
// and in the header, as the PNG frames carry it: `spume/record` (what the frame was drawn from,
// render/stage/render_stage.h), `spume/keysDigest` (its digest), `spume/scene`, `spume/version`,
// and `comments` saying how the layers rebuild beauty.
#include <filesystem>
#include <optional>
#include <string>

#include "render/frame/frame_layers.h"

namespace spume {

struct FrameProvenance {
  std::string scene;
  std::string record;  // compact JSON
};

// Atomic; throws Error naming `path`.
void write_frame_exr(const std::filesystem::path& path, const FrameLayers& frame, const FrameProvenance& provenance);

// The `spume/record` of a frame's EXR; nullopt for a missing or unreadable file.
std::optional<std::string> read_frame_exr_record(const std::filesystem::path& path);

// What an EXR frame holds, for `spume info`: size, compression, channels by layer with how much of
// the image each layer covers, the range of Z, the largest motion, and where spume's frames came from.
// Throws Error naming the file when it is not a readable OpenEXR file.
std::string describe_frame_exr(const std::filesystem::path& path);

// spume's version, as the EXR header gives it.
const char* spume_version();

}  // namespace spume
