#include "render/app/movie.h"

#include <cstdlib>
#include <regex>

#include "sim/core/error.h"

namespace spume {
namespace {

// ffmpeg's image2 demuxer takes printf patterns only: #### -> %04d.
std::string printf_pattern(const std::string& pattern) {
  std::smatch m;
  static const std::regex hashes("#+");
  if (!std::regex_search(pattern, m, hashes)) return pattern;
  return m.prefix().str() + "%0" + std::to_string(m.length(0)) + "d" + m.suffix().str();
}

std::string quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace

void write_movie(const std::string& pattern, int first_frame, double fps, const std::filesystem::path& output,
                 bool quiet) {
  if (std::system("command -v ffmpeg > /dev/null 2>&1") != 0)
    fail("--movie: ffmpeg is not installed (apt-get install ffmpeg); the PNG frames are written");
  const std::filesystem::path partial = output.string() + ".partial.mp4";
  const std::string command = "ffmpeg -y -loglevel error -framerate " + std::to_string(fps) + " -start_number " +
                              std::to_string(first_frame) + " -i " + quoted(printf_pattern(pattern)) +
                              " -c:v libx264 -pix_fmt yuv420p -vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' " +
                              quoted(partial.string()) + (quiet ? " > /dev/null 2>&1" : "");
  if (std::system(command.c_str()) != 0) {
    std::error_code ec;
    std::filesystem::remove(partial, ec);
    fail("--movie: ffmpeg failed: ", command);
  }
  std::filesystem::rename(partial, output);
}

}  // namespace spume
