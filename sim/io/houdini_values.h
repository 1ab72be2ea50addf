#pragma once
// The value block of a Houdini geometry attribute: `count` tuples of `size` numbers, in one of the
// three layouts Houdini writes:
//   "tuples"       an array of `count` tuples (each an array of `size` numbers)
//   "arrays"       `size` arrays of `count` numbers (one per component)
//   "rawpagedata"  paged: "pagesize" elements per page; "packing" splits the tuple into parts (the whole
//                  tuple when absent); "constantpageflags" holds one flag per page for each part. Page
//                  by page, part by part, the data holds one tuple part when the page is constant for
//                  that part, and one part per element (the last page shorter) otherwise.
// Numbers come as uniform arrays of any storage (int8..int64, uint8/16, fpreal16/32/64) or as plain
// arrays of numbers.
#include <cstdint>
#include <vector>

#include "sim/io/houdini_json.h"

namespace spume::hjson {

// Reads the value block (a key/value array) at the reader's position into `out` (count * size numbers,
// element-major). `what` names the attribute in errors. Fails on any size or layout that does not
// account for exactly `count` tuples.
void read_values(Reader& r, uint64_t count, int size, std::vector<double>& out, std::string_view what);

}  // namespace spume::hjson

namespace spume::hjson {
// A short array of numbers (uniform or plain), e.g. the info block's bounds.
std::vector<double> read_number_list(Reader& r, std::string_view what);
}  // namespace spume::hjson
