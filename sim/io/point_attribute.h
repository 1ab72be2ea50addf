#pragma once
// A per-point attribute as a file declares it, for `spume info` listings.
#include <string>

namespace spume {

struct PointAttribute {
  std::string name;
  std::string type;    // as the format names it: "float", "int", "vector", "Float32", "uchar", ...
  int components = 1;  // values per point
};

}  // namespace spume
