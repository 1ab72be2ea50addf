#include "cache_state.h"

#include <fstream>
#include <sstream>

#include "core/atomic_file.h"
#include "core/error.h"

namespace spume {
namespace {

std::filesystem::path fingerprint_path(const std::filesystem::path& dir) { return dir / "fingerprint.json"; }

}  // namespace

bool cache_is_current(const std::filesystem::path& dir, const std::string& fingerprint,
                      const std::vector<std::filesystem::path>& frames) {
  std::ifstream in(fingerprint_path(dir), std::ios::binary);
  if (!in) return false;
  std::ostringstream text;
  text << in.rdbuf();
  if (text.str() != fingerprint + "\n") return false;
  for (const auto& f : frames)
    if (!std::filesystem::is_regular_file(f)) return false;
  return true;
}

void mark_cache_started(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  std::filesystem::remove(fingerprint_path(dir), ec);
  if (std::filesystem::exists(fingerprint_path(dir)))
    fail(fingerprint_path(dir).string(), ": cannot remove the stale cache fingerprint: ", ec.message());
}

void mark_cache_complete(const std::filesystem::path& dir, const std::string& fingerprint) {
  write_file_atomically(fingerprint_path(dir), [&](std::ostream& out) { out << fingerprint << '\n'; });
}

}  // namespace spume
