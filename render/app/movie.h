#pragma once
// --movie: the rendered PNG sequence as an H.264 MP4 via ffmpeg, when ffmpeg is installed.
#include <filesystem>
#include <string>

namespace spume {

// Encodes the frames of `pattern` (as in render.frames: %04d, %d or ####) from `first_frame` on at
// `fps` into `output`, written atomically. Throws Error when ffmpeg is missing or fails.
void write_movie(const std::string& pattern, int first_frame, double fps, const std::filesystem::path& output,
                 bool quiet);

}  // namespace spume
