#pragma once
// Which caches on disk are current. A cache folder holds per-frame files plus `fingerprint.json`, the
// canonical scene keys it was made from (SimScene::*_fingerprint), written only once every frame is
// on disk. A stage reuses a folder when the fingerprint matches and every frame it needs exists;
// otherwise it removes the fingerprint (so an interrupted run is never mistaken for a finished one)
// and makes the frames again.
#include <filesystem>
#include <string>
#include <vector>

namespace spume {

bool cache_is_current(const std::filesystem::path& dir, const std::string& fingerprint,
                      const std::vector<std::filesystem::path>& frames);
void mark_cache_started(const std::filesystem::path& dir);
void mark_cache_complete(const std::filesystem::path& dir, const std::string& fingerprint);

}  // namespace spume
