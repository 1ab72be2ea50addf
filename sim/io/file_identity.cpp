#include "sim/io/file_identity.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <ctime>
#include <fstream>

#include "sim/core/error.h"

namespace spume {

std::string FileIdentity::text() const {
  if (mtime_ns == 0) {
    char crc_text[16];
    std::snprintf(crc_text, sizeof crc_text, "%08x", crc);
    return str(size, " bytes, CRC-32 ", crc_text);
  }
  const std::time_t seconds = std::time_t(mtime_ns / 1000000000);
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char when[64];
  std::strftime(when, sizeof when, "%Y-%m-%d %H:%M:%S", &utc);
  char nanos[16];
  std::snprintf(nanos, sizeof nanos, ".%09lld", static_cast<long long>(mtime_ns % 1000000000));
  return str(size, " bytes, modified ", when, nanos, " UTC");
}

FileIdentity file_identity(const std::filesystem::path& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) fail(path.string(), ": cannot read the file's status (", std::strerror(errno), ")");
  if (!S_ISREG(st.st_mode)) fail(path.string(), ": not a regular file");
  FileIdentity id;
  id.size = uint64_t(st.st_size);
  const std::string extension = path.extension().string();
  if ((extension == ".spf" || extension == ".spd") && id.size >= 4) {
    std::ifstream in(path, std::ios::binary);
    unsigned char tail[4];
    in.seekg(-4, std::ios::end);
    if (!in.read(reinterpret_cast<char*>(tail), 4)) fail(path.string(), ": cannot read the cache's CRC");
    id.crc = uint32_t(tail[0]) | uint32_t(tail[1]) << 8 | uint32_t(tail[2]) << 16 | uint32_t(tail[3]) << 24;
    return id;
  }
  id.mtime_ns = int64_t(st.st_mtim.tv_sec) * 1000000000 + int64_t(st.st_mtim.tv_nsec);
  return id;
}

}  // namespace spume
