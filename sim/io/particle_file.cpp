#include "sim/io/particle_file.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string_view>
#include <system_error>

#include "sim/core/error.h"
#include "sim/io/bgeo.h"
#include "sim/io/io_bytes.h"
#include "sim/io/ply.h"
#include "sim/io/spume_cache.h"
#include "sim/io/vtk.h"

namespace spume {
namespace {

constexpr const char* kAllowed = ".bgeo, .bgeo.gz, .bhclassic, .bhclassic.gz, .vtk, .vtu, .vtp, .ply, .spf, .spd";

constexpr const char* kHoudiniHint =
    "export classic .bgeo or .bhclassic geometry from Houdini instead (see the README, Inputs)";

// Houdini's binary JSON geometry starts 7F 'N' 'S' 'J' whatever the file is called.
bool starts_with_newer_houdini_magic(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  char magic[4] = {};
  return in.read(magic, 4) && std::string_view(magic, 4) == std::string_view("\x7fNSJ", 4);
}

void require_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) fail(path.string(), ": no such file");
  if (std::filesystem::is_directory(path, ec)) fail(path.string(), ": is a directory, not a particle file");
}

std::string vec_str(const Vec3f& v) { return str("(", v.x(), ", ", v.y(), ", ", v.z(), ")"); }

std::string bounds_str(const Aabb& b) { return b.empty() ? "(no points)" : vec_str(b.min) + " .. " + vec_str(b.max); }

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

}  // namespace

ParticleFormat particle_format(const std::filesystem::path& path) {
  const std::string name = io::lower_file_name(path);
  using io::ends_with;
  if (ends_with(name, ".bgeo") || ends_with(name, ".bgeo.gz") || ends_with(name, ".bhclassic") ||
      ends_with(name, ".bhclassic.gz"))
    return ParticleFormat::Bgeo;
  if (ends_with(name, ".vtk")) return ParticleFormat::VtkLegacy;
  if (ends_with(name, ".vtu") || ends_with(name, ".vtp")) return ParticleFormat::VtkXml;
  if (ends_with(name, ".ply")) return ParticleFormat::Ply;
  if (ends_with(name, ".spf")) return ParticleFormat::FluidCache;
  if (ends_with(name, ".spd")) return ParticleFormat::DiffuseCache;
  if (ends_with(name, ".sc") || starts_with_newer_houdini_magic(path))
    fail(path.string(), ": Houdini's newer compressed geometry format (.bgeo.sc, binary JSON) is not supported; ",
         kHoudiniHint);
  fail(path.string(), ": unknown particle file extension '", path.extension().string(), "'; allowed ", kAllowed);
}

FluidFrame read_fluid_file(const std::filesystem::path& path) {
  require_file(path);
  switch (particle_format(path)) {
    case ParticleFormat::Bgeo: return read_bgeo(path);
    case ParticleFormat::VtkLegacy: return read_vtk(path);
    case ParticleFormat::VtkXml: return read_vtu(path);
    case ParticleFormat::Ply: return read_ply(path);
    case ParticleFormat::FluidCache: return read_fluid_cache(path);
    case ParticleFormat::DiffuseCache:
      fail(path.string(), ": is a spume diffuse cache (.spd), not a fluid frame; fluid files are .bgeo, .vtk, .vtu, "
           ".vtp, .ply or .spf");
  }
  fail(path.string(), ": unsupported particle format");
}

std::string describe_particle_file(const std::filesystem::path& path) {
  require_file(path);
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
      if (info.trailing_data_skipped)
        out << "  note: " << info.primitive_count << " primitives / groups after the points were not read\n";
      if (has_attribute(info.point_attributes, "type") && has_attribute(info.point_attributes, "lifetime")) {
        out << "  content: spume diffuse particles\n";
        describe_diffuse(out, read_bgeo_diffuse(path));
      } else {
        describe_fluid(out, read_bgeo(path));
      }
      break;
    }
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

}  // namespace spume
