#pragma once
// VTK particle files: legacy .vtk (ASCII or BINARY, big-endian) and XML .vtu/.vtp.
//
// Legacy: DATASET POLYDATA or UNSTRUCTURED_GRID; POINTS of any numeric type; cell sections (VERTICES,
// CELLS, CELL_TYPES, ... in the 4.x and the 5.1 OFFSETS/CONNECTIVITY form) are skipped; POINT_DATA
// arrays may be SCALARS, VECTORS or FIELD arrays. This is what SPlisHSPlasH writes (POINTS, CELLS,
// CELL_TYPES, POINT_DATA with SCALARS id and FIELD FieldData velocity ...). A dataset-level FIELD array
// TIME (one value) gives the frame time.
//
// XML (.vtu UnstructuredGrid, .vtp PolyData): DataArray format="ascii", "binary" (base64, header_type
// UInt32 or UInt64, optionally compressor="vtkZLibDataCompressor") and "appended" (encoding raw or
// base64). Several Pieces are concatenated. LZ4/LZMA compression is rejected with a re-export hint.
//
// Arrays used: velocity from `velocity`, `v` or `Velocity` (3 components; the first present wins),
// ids from `id`, `ids` or `ID` (integers 0 .. 2^32-1), masses from `mass`.
#include <filesystem>
#include <vector>

#include "sim/core/frames.h"
#include "sim/io/point_attribute.h"

namespace spume {

// *attributes receives every point-data array (name, type as written, components).
FluidFrame read_vtk(const std::filesystem::path& path, std::vector<PointAttribute>* attributes = nullptr);
FluidFrame read_vtu(const std::filesystem::path& path, std::vector<PointAttribute>* attributes = nullptr);

// Legacy BINARY UNSTRUCTURED_GRID with one vertex cell per particle (so ParaView draws them) and
// FIELD arrays id (unsigned_int), velocity (float, 3) and mass (float) for what the frame has.
void write_vtk(const std::filesystem::path& path, const FluidFrame& frame);

namespace io {
// Which array a name feeds (shared by the two readers).
enum class VtkRole { None, Velocity, Id, Mass };
VtkRole vtk_role(std::string_view name, int components);
}  // namespace io

}  // namespace spume
