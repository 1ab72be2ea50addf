#include "sim/io/particle_file.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string_view>
#include <system_error>

#include "sim/core/error.h"
#include "sim/core/out_of_memory.h"
#include "sim/core/unusable_masses.h"
#include "sim/io/attribute_names.h"
#include "sim/io/bgeo.h"
#include "sim/io/fluid_import.h"
#include "sim/io/houdini_geometry.h"
#include "sim/io/io_bytes.h"
#include "sim/io/ply.h"
#include "sim/io/spume_cache.h"
#include "sim/io/vdb_points.h"
#include "sim/io/vtk.h"

namespace spume {
namespace {

constexpr const char* kAllowed = ".bgeo, .bgeo.gz, .bgeo.sc, .bhclassic, .bhclassic.gz, .vtk, .vtu, .vtp, .ply, .vdb, .spf, .spd";

void require_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) fail(path.string(), ": no such file");
  if (std::filesystem::is_directory(path, ec)) fail(path.string(), ": is a directory, not a particle file");
}

std::string vec_str(const Vec3f& v) { return str("(", v.x(), ", ", v.y(), ", ", v.z(), ")"); }

// Bounds to 0.1 mm, or to 1e-3 of the extent when that is finer: a fluid 10 km from the origin keeps its
// millimetres (6 significant digits would round it to 10 cm), a 1 cm drop its hundredths of a millimetre.
std::string bounds_str(const Aabb& b) {
  if (b.empty()) return "(no points)";
  const float extent = (b.max - b.min).maxCoeff();
  const double step = extent > 0.0f ? std::min(1e-4, 1e-3 * double(extent)) : 1e-4;
  const int decimals = std::clamp(int(std::ceil(-std::log10(step) - 1e-3)), 4, 9);
  auto coordinate = [&](float v) {
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", decimals, double(v));
    std::string out = text;
    if (out.find('.') != std::string::npos) {
      while (out.back() == '0') out.pop_back();
      if (out.back() == '.') out.pop_back();
    }
    return out == "-0" ? std::string("0") : out;
  };
  auto point = [&](const Vec3f& v) { return str("(", coordinate(v.x()), ", ", coordinate(v.y()), ", ", coordinate(v.z()), ")"); };
  return point(b.min) + " .. " + point(b.max);
}

template <typename Positions>
Aabb bounds_of(const Positions& positions) {
  Aabb b;
  for (const Vec3f& p : positions) b.extend(p);
  return b;
}

float max_speed(const std::vector<Vec3f>& velocities) {
  float m = 0.0f;
  for (const Vec3f& v : velocities) m = std::max(m, v.norm());
  return m;
}

std::string attribute_list(const std::vector<PointAttribute>& attrs) {
  if (attrs.empty()) return "(none)";
  std::string out;
  for (const PointAttribute& a : attrs) out += str(out.empty() ? "" : ", ", a.name, " (", a.type, ", ", a.components, ")");
  return out;
}

// The lines every fluid frame gets, whatever its format.
void describe_fluid(std::ostringstream& out, const FluidFrame& f) {
  out << "  points: " << f.size() << "\n";
  out << "  bounds: " << bounds_str(bounds_of(f.positions)) << "\n";
  out << "  velocities: " << (f.has_velocities() ? str("yes, max speed ", max_speed(f.velocities), " m/s") : "no") << "\n";
  if (f.has_ids()) {
    const auto [lo, hi] = std::minmax_element(f.ids.begin(), f.ids.end());
    out << "  ids: " << *lo << " .. " << *hi << "\n";
  } else {
    out << "  ids: none (frames are paired by index only where the count and the order are kept)\n";
  }
  if (!f.masses.empty()) {
    const auto [lo, hi] = std::minmax_element(f.masses.begin(), f.masses.end());
    out << "  masses: " << *lo << " .. " << *hi << " kg\n";
    if (const UnusableMasses odd = unusable_masses(f.masses); odd.count > 0)
      out << "  odd: " << odd.describe(f.masses.size()) << ", which no kinetic energy can be weighed with; a run "
          << "gives those particles the uniform mass rho0 (2r)^3 and says so\n";
  }
}

void describe_diffuse(std::ostringstream& out, const DiffuseFrame& f) {
  const auto counts = f.count_by_type();
  out << "  particles: " << f.size() << " (spray " << counts[0] << ", foam " << counts[1] << ", bubble " << counts[2]
      << ")\n";
  out << "  bounds: " << bounds_str(bounds_of(f.positions)) << "\n";
  if (f.size() > 0) {
    const auto [lo, hi] = std::minmax_element(f.lifetimes.begin(), f.lifetimes.end());
    out << "  lifetime: " << *lo << " .. " << *hi << " s\n";
    out << "  max speed: " << max_speed(f.velocities) << " m/s\n";
  }
}

bool has_attribute(const std::vector<PointAttribute>& attrs, std::string_view name) {
  return std::any_of(attrs.begin(), attrs.end(), [&](const PointAttribute& a) { return a.name == name; });
}

std::string range_str(const Aabb& b) { return vec_str(b.min) + " .. " + vec_str(b.max); }

void describe_houdini(std::ostringstream& out, const std::filesystem::path& path) {
  HoudiniGeometryInfo info;
  const FluidFrame frame = read_houdini_geometry(path, &info);
  out << "  format: Houdini geometry, binary JSON" << (info.file_version.empty() ? "" : " (Houdini " + info.file_version + ")");
  if (info.container == "gzip") out << ", gzip-compressed";
  if (info.chunks > 0) out << ", Blosc-compressed in " << info.chunks << " chunk" << (info.chunks > 1 ? "s" : "");
  out << ", " << info.json_bytes << " bytes of JSON\n";
  out << "  points in the file: " << info.point_count << ", bounds " << bounds_str(info.point_bounds) << "\n";
  if (info.primitive_count > 0)
    out << "  primitives: " << info.primitive_count << (info.primitive_summary.empty() ? "" : " (" + info.primitive_summary + ")")
        << ", not read (spume reads points)\n";
  out << "  attributes: " << attribute_list(info.point_attributes) << "\n";
  if (!info.velocity_attribute.empty())
    out << "  velocity from '" << info.velocity_attribute << "', range over all points " << range_str(info.velocity_range) << "\n";
  if (info.points_without_id > 0)
    out << "  left out: " << info.points_without_id
        << " points with a negative id (Houdini's -1: no id, e.g. a mesh merged into the cache); they are not particles\n";
  if (info.info_bounds) {
    const Aabb& b = *info.info_bounds;
    const bool same = !info.point_bounds.empty() && b.min == info.point_bounds.min && b.max == info.point_bounds.max;
    const bool inside = !info.point_bounds.empty() && (b.min.array() <= info.point_bounds.min.array()).all() &&
                        (info.point_bounds.max.array() <= b.max.array()).all();
    out << "  Houdini's info block: bounds " << bounds_str(b)
        << (same ? " (the points' bounds: agree)" : inside ? " (holds the points; it includes the primitives)" :
            " (DISAGREES with the points read)")
        << "\n";
  }
  if (!info.info_attribute_ranges.empty()) out << "  Houdini's info block: attribute ranges " << info.info_attribute_ranges << "\n";
  describe_fluid(out, frame);
}

// Runs fn, which reads `path`: running out of memory names the file and its size.
template <typename Fn>
auto reading_file(const std::filesystem::path& path, Fn&& fn) {
  try {
    return fn();
  } catch (const std::bad_alloc&) {
    std::error_code ec;
    const uint64_t bytes = std::filesystem::file_size(path, ec);
    fail(path.string(), ": ", out_of_memory_message(str("reading this file", ec ? "" : " of " + byte_size_text(bytes))));
  }
}

std::string describe_file(const std::filesystem::path& path);

}  // namespace

ParticleFormat particle_format(const std::filesystem::path& path) {
  const std::string name = io::lower_file_name(path);
  using io::ends_with;
  if (ends_with(name, ".bgeo.sc")) return ParticleFormat::HoudiniGeometry;
  if (ends_with(name, ".bgeo") || ends_with(name, ".bgeo.gz") || ends_with(name, ".bhclassic") ||
      ends_with(name, ".bhclassic.gz"))
    return is_houdini_geometry(path) ? ParticleFormat::HoudiniGeometry : ParticleFormat::Bgeo;
  if (ends_with(name, ".vtk")) return ParticleFormat::VtkLegacy;
  if (ends_with(name, ".vtu") || ends_with(name, ".vtp")) return ParticleFormat::VtkXml;
  if (ends_with(name, ".ply")) return ParticleFormat::Ply;
  if (ends_with(name, ".vdb")) return ParticleFormat::Vdb;
  if (ends_with(name, ".spf")) return ParticleFormat::FluidCache;
  if (ends_with(name, ".spd")) return ParticleFormat::DiffuseCache;
  if (is_houdini_geometry(path)) return ParticleFormat::HoudiniGeometry;  // Houdini's binary JSON, any name
  fail(path.string(), ": unknown particle file extension '", path.extension().string(), "'; allowed ", kAllowed);
}

namespace {

FluidFrame read_as_stored(const std::filesystem::path& path, const FluidReadOptions& options) {
  switch (particle_format(path)) {
    case ParticleFormat::Bgeo: return read_bgeo(path);
    case ParticleFormat::HoudiniGeometry: return read_houdini_geometry(path);
    case ParticleFormat::VtkLegacy: return read_vtk(path);
    case ParticleFormat::VtkXml: return read_vtu(path);
    case ParticleFormat::Ply: return read_ply(path);
    case ParticleFormat::Vdb: return read_vdb_points(path, options.vdb_grid);
    case ParticleFormat::FluidCache: return read_fluid_cache(path);
    case ParticleFormat::DiffuseCache:
      fail(path.string(), ": is a spume diffuse cache (.spd), not a fluid frame; fluid files are .bgeo, .bgeo.sc, .vtk, "
           ".vtu, .vtp, .ply, .vdb or .spf");
  }
  fail(path.string(), ": unsupported particle format");
}

// A file of volumes: each grid's class, voxels and (float grids) range and integral. spume's fog export
// (io/fog_volumes.h) is named as such, since its integrals are its particles' volumes.
void describe_volumes(std::ostringstream& out, const VdbContents& contents) {
  auto has = [&](const char* name) {
    return std::any_of(contents.volumes.begin(), contents.volumes.end(),
                       [&](const VdbVolumeInfo& v) { return v.name == name; });
  };
  const bool fog = has("density") && has("v") && (has("spray") || has("foam") || has("bubble"));
  out << "  content: " << (fog ? "spume fog volumes (output.fog)" : "volumes, no particles") << ", frame "
      << contents.frame_index << ", time " << contents.time << " s\n";
  for (const VdbVolumeInfo& v : contents.volumes) {
    out << "    '" << v.name << "': " << v.grid_class << ", " << v.active_voxels << " active voxels";
    if (v.scalar)
      out << ", values " << v.min << " .. " << v.max << ", integral " << v.integral
          << (!fog ? " (values x m^3)" : v.name == "density" ? " m^3" : " m^3 (the volume of its particles' spheres)");
    out << "\n";
  }
}

void describe_vdb(std::ostringstream& out, const std::filesystem::path& path) {
  VdbPointsInfo info;
  VdbContents contents = read_vdb_contents(path, "", &info);
  FluidFrame& frame = contents.fluid;
  out << "  format: OpenVDB, " << info.grids.size() << " grid" << (info.grids.size() == 1 ? "" : "s") << "\n";
  for (const VdbGridInfo& g : info.grids)
    out << "    grid '" << g.name << "': " << g.type << ", voxel size " << g.voxel_size << " m, "
        << (g.points ? str(g.count, " points") : str(g.count, " active voxels")) << (g.used ? " (read)" : "") << "\n";
  if (!contents.volumes.empty()) {
    describe_volumes(out, contents);
    return;
  }
  out << "  point attributes:";
  for (const VdbAttributeInfo& a : info.attributes)
    out << " " << (info.grids.size() > 1 ? a.grid + "." : "") << a.name << " (" << a.type << ", " << a.codec << ")";
  out << "\n";
  if (contents.diffuse) {
    out << "  content: spume diffuse particles (output.vdb), frame " << contents.frame_index << ", time "
        << contents.time << " s\n";
    describe_diffuse(out, *contents.diffuse);
    if (!contents.diffuse_ages.empty()) {
      const auto [young, old] = std::minmax_element(contents.diffuse_ages.begin(), contents.diffuse_ages.end());
      out << "  age: " << *young << " .. " << *old << " s since birth (Houdini's age; life = age + lifetime)\n";
    }
    if (contents.diffuse->size() > 0) {
      const auto [lo, hi] = std::minmax_element(contents.diffuse->ids.begin(), contents.diffuse->ids.end());
      out << "  ids: " << *lo << " .. " << *hi << " (64-bit: parent fluid id, birth step, sample)\n";
    }
    return;
  }
  out << "  spume reads: " << info.choice << "; positions P through the grid's transform; velocity "
      << (info.velocity_attribute.empty() ? "none (" + io::attribute_names_text(io::AttributeRole::Velocity) + ")"
                                          : "from '" + info.velocity_attribute + "'")
      << "; ids " << (info.id_attribute.empty() ? "none (" + io::attribute_names_text(io::AttributeRole::Id) + ")"
                                                : "from '" + info.id_attribute + "'")
      << "; masses " << (info.mass_attribute.empty() ? "none (" + io::attribute_names_text(io::AttributeRole::Mass) + ")"
                                                     : "from '" + info.mass_attribute + "'")
      << "\n";
  // What a scene with the default keys would make of it (fluid.up_axis "auto", no fluid.velocity_scale).
  const FluidImport import = resolve_fluid_import(path, "auto", "", std::nullopt, 0.0);
  if (import.read.up == UpAxis::Y) out << "  up axis: y (no Mantaflow config beside the file; fluid.up_axis = \"z\" turns a Z-up cache)\n";
  for (const std::string& note : import.notes) out << "  " << note << "\n";
  if (import.mantaflow)
    out << "  particles: flip (fluid.particles \"auto\" for a Mantaflow cache: velocities averaged over 2 h for the "
           "potentials, counts against the frame's own particle density; MODEL.md §9.2)\n";
  to_y_up(frame, import.read.up);
  if (import.velocity_scale != 1.0f)
    for (Vec3f& v : frame.velocities) v *= import.velocity_scale;
  if (import.read.up != UpAxis::Y || import.velocity_scale != 1.0f)
    out << "  below: as spume takes it" << (import.read.up != UpAxis::Y ? ", Y-up" : "")
        << (import.velocity_scale != 1.0f ? ", velocities in m/s" : "") << "\n";
  describe_fluid(out, frame);
}

}  // namespace

FluidFrame read_fluid_file(const std::filesystem::path& path, const FluidReadOptions& options) {
  require_file(path);
  FluidFrame frame = reading_file(path, [&] { return read_as_stored(path, options); });
  to_y_up(frame, options.up);
  if (!options.stored_masses) frame.masses.clear();
  return frame;
}

std::string describe_particle_file(const std::filesystem::path& path) {
  require_file(path);
  return reading_file(path, [&] { return describe_file(path); });
}

namespace {

std::string describe_file(const std::filesystem::path& path) {
  const ParticleFormat format = particle_format(path);
  std::ostringstream out;
  out << path.string() << "\n";
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path, ec);
  switch (format) {
    case ParticleFormat::Bgeo: {
      const BgeoInfo info = read_bgeo_info(path);
      out << "  format: classic BGEO version " << info.version << (info.gzipped ? ", gzip-compressed" : "") << "\n";
      out << "  attributes: " << attribute_list(info.point_attributes) << "\n";
      if (!info.detail_attributes.empty()) out << "  detail attributes: " << attribute_list(info.detail_attributes) << "\n";
      if (!info.point_groups.empty()) {
        out << "  point groups:";
        for (const auto& [name, members] : info.point_groups) out << " " << name << " (" << members << ")";
        out << "\n";
      }
      if (info.trailing_data_skipped)
        out << "  note: " << info.primitive_count << " primitives and the groups after the points were not read\n";
      if (has_attribute(info.point_attributes, "type") && has_attribute(info.point_attributes, "lifetime")) {
        out << "  content: spume diffuse particles\n";
        describe_diffuse(out, read_bgeo_diffuse(path));
      } else {
        describe_fluid(out, read_bgeo(path));
      }
      break;
    }
    case ParticleFormat::HoudiniGeometry: describe_houdini(out, path); break;
    case ParticleFormat::Vdb: describe_vdb(out, path); break;
    case ParticleFormat::VtkLegacy:
    case ParticleFormat::VtkXml:
    case ParticleFormat::Ply: {
      std::vector<PointAttribute> attrs;
      const FluidFrame frame = format == ParticleFormat::VtkLegacy ? read_vtk(path, &attrs)
                               : format == ParticleFormat::VtkXml  ? read_vtu(path, &attrs)
                                                                   : read_ply(path, &attrs);
      out << "  format: " << (format == ParticleFormat::VtkLegacy ? "legacy VTK" : format == ParticleFormat::VtkXml ? "XML VTK" : "PLY")
          << "\n";
      out << "  attributes: " << attribute_list(attrs) << "\n";
      describe_fluid(out, frame);
      break;
    }
    case ParticleFormat::FluidCache: {
      FluidCacheHeader h;
      const FluidFrame frame = read_fluid_cache(path, &h);
      out << "  format: spume fluid cache version " << h.version << "\n";
      out << "  frame: " << h.frame_index << ", time " << h.time << " s, particle radius " << h.particle_radius << " m\n";
      describe_fluid(out, frame);
      break;
    }
    case ParticleFormat::DiffuseCache: {
      DiffuseCacheHeader h;
      const DiffuseFrame frame = read_diffuse_cache(path, &h);
      out << "  format: spume diffuse cache version " << h.version << "\n";
      out << "  frame: " << h.frame_index << ", time " << h.time << " s\n";
      describe_diffuse(out, frame);
      break;
    }
  }
  if (!ec) out << "  file size: " << bytes << " bytes\n";
  return out.str();
}

}  // namespace

}  // namespace spume
