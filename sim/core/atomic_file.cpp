#include "atomic_file.h"

#include <cstdio>
#include <fstream>
#include <system_error>
#include <unistd.h>

#include "error.h"

namespace spume {

void write_file_atomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (path.has_parent_path()) {
    fs::create_directories(path.parent_path(), ec);
    if (ec) fail(path.string(), ": cannot create directory ", path.parent_path().string(), ": ", ec.message());
  }
  // Unique per host and process: farm nodes share output folders, and pids repeat across hosts.
  char host[256] = {};
  if (::gethostname(host, sizeof host - 1) != 0 || !host[0]) std::snprintf(host, sizeof host, "unknown");
  fs::path tmp = path;
  tmp += str(".tmp.", host, ".", ::getpid());
  try {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) fail(path.string(), ": cannot open ", tmp.string(), " for writing");
    write(out);
    out.flush();
    if (!out) fail(path.string(), ": write failed (disk full?)");
    out.close();
    fs::rename(tmp, path, ec);
    if (ec) fail(path.string(), ": cannot rename temporary file into place: ", ec.message());
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
}

}  // namespace spume
