#pragma once
// `spume --version`: spume's version and how it was built (compiler, build type), and the versions of
// the libraries that shape its results (Embree, Mesa, Eigen, oneTBB, Bullet), for bug reports and for
// knowing whether two machines can render byte-identical farm frames.
#include <string>

namespace spume {

// Several lines, the first "spume X.Y". Opens a 1x1 OSMesa context to ask Mesa its version (a few
// milliseconds); says so when no context can be made.
std::string version_text();

}  // namespace spume
