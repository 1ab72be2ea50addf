#pragma once
// One entry point for particle files of any supported format, chosen by extension.
//   .bgeo .bgeo.gz .bhclassic .bhclassic.gz  classic BGEO (io/bgeo.h), or, when the content is Houdini 12+
//                                            binary JSON, Houdini geometry (io/houdini_geometry.h)
//   .bgeo.sc                                  Houdini geometry, Blosc-compressed (io/houdini_geometry.h)
//   .vtk                                      legacy VTK (io/vtk.h)
//   .vtu .vtp                                 XML VTK (io/vtk.h)
//   .ply                                      PLY (io/ply.h)
//   .vdb                                      OpenVDB point data grids (io/vdb_points.h)
//   .spf                                      spume fluid cache (io/spume_cache.h)
//   .spd                                      spume diffuse cache (describe only; not a fluid file)
#include <filesystem>
#include <string>

#include "sim/core/frames.h"
#include "sim/io/fluid_read_options.h"

namespace spume {

enum class ParticleFormat { Bgeo, HoudiniGeometry, VtkLegacy, VtkXml, Ply, Vdb, FluidCache, DiffuseCache };

// The format a file name implies (a .bgeo's first bytes tell classic from binary JSON; any file starting
// with Houdini's binary JSON magic is Houdini geometry); Error listing the allowed extensions otherwise.
ParticleFormat particle_format(const std::filesystem::path& path);

// Reads a fluid frame from any fluid format; the frame is validated (finite values, unique ids) with
// the path in every message. "<path>: no such file" when it is missing. Empty frames are returned as such.
// `options`: a Z-up cache is turned to Y-up; a .vdb's point grid to read.
FluidFrame read_fluid_file(const std::filesystem::path& path, const FluidReadOptions& options = {});

// Multi-line human-readable summary for `spume info`: format, point count, attributes, bounds; for
// diffuse caches (and spume's diffuse BGEO) counts per type and the lifetime range; for .vdb the grids,
// the point attributes, and what spume reads (the up axis and velocity units a scene would take by default).
std::string describe_particle_file(const std::filesystem::path& path);

}  // namespace spume
