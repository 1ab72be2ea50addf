#include "sim/io/mantaflow_config.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <system_error>

#include "sim/core/error.h"
#include "sim/io/io_bytes.h"

namespace spume {
namespace {

// Byte offsets of the fields spume uses (each int and float 4 bytes; see the header).
constexpr size_t kRes = 4, kDx = 16, kDt = 20, kP0 = 24, kP1 = 36, kObmat = 84, kTimeTotal = 196, kCacheId = 200;
constexpr size_t kMinBytes = kObmat + 64;  // up to the object matrix: enough for the units
constexpr size_t kFullBytes = kCacheId + 4;
// Blender's frame length: DT_DEFAULT 0.1 Mantaflow time units per frame at 25 fps (fluid.cc).
constexpr double kTimeUnitsPerSecond = 0.1 * 25.0;

template <typename T>
T field(const std::string& bytes, size_t offset) {
  T v;
  std::memcpy(&v, bytes.data() + offset, sizeof(T));
  return v;
}

// "fluid_data_0030.vdb" -> "0030"; "" when the name is not Mantaflow's.
std::string frame_digits(const std::string& name) {
  const std::string prefix = "fluid_data_";
  if (name.rfind(prefix, 0) != 0) return "";
  const size_t dot = name.find('.', prefix.size());
  if (dot == std::string::npos || name.substr(dot) != ".vdb") return "";
  const std::string digits = name.substr(prefix.size(), dot - prefix.size());
  if (digits.size() < 4 || !std::all_of(digits.begin(), digits.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); }))
    return "";
  return digits;
}

std::filesystem::path config_for(const std::filesystem::path& data_file, const std::string& digits) {
  return data_file.parent_path().parent_path() / "config" / ("config_" + digits + ".uni");
}

bool is_file(const std::filesystem::path& p) {
  std::error_code ec;
  return std::filesystem::is_regular_file(p, ec);
}

}  // namespace

std::optional<std::filesystem::path> mantaflow_config_path(const std::filesystem::path& data_file) {
  const std::string digits = frame_digits(data_file.filename().string());
  if (digits.empty()) return std::nullopt;
  const std::filesystem::path config = config_for(data_file, digits);
  if (!is_file(config)) return std::nullopt;
  return config;
}

MantaflowConfig read_mantaflow_config(const std::filesystem::path& file) {
  const std::string where = file.string();
  const std::string raw = io::read_file_bytes(file);
  if (!io::has_gzip_magic(raw)) fail(where, ": not a Mantaflow config (expected a gzip stream)");
  const std::string bytes = io::gunzip(raw, where);
  if (bytes.size() < kMinBytes)
    fail(where, ": ", bytes.size(), " bytes; a Mantaflow config holds at least ", kMinBytes, " (cut short?)");
  MantaflowConfig c;
  c.file = file;
  for (int a = 0; a < 3; ++a) c.resolution[a] = field<int32_t>(bytes, kRes + 4 * size_t(a));
  c.dx = field<float>(bytes, kDx);
  c.dt = field<float>(bytes, kDt);
  for (int a = 0; a < 3; ++a) {
    if (c.resolution[a] <= 0 || c.resolution[a] > 1 << 16)
      fail(where, ": resolution ", c.resolution[0], " x ", c.resolution[1], " x ", c.resolution[2], " is not a grid");
    const float extent = field<float>(bytes, kP1 + 4 * size_t(a)) - field<float>(bytes, kP0 + 4 * size_t(a));
    // Column a of Blender's object matrix (column-major float[4][4]) is the domain's axis a, scaled.
    Vec3f column;
    for (int r = 0; r < 3; ++r) column[r] = field<float>(bytes, kObmat + 16 * size_t(a) + 4 * size_t(r));
    c.domain_size[a] = extent * column.norm();
    if (!(c.domain_size[a] > 0.0f) || !std::isfinite(c.domain_size[a]))
      fail(where, ": domain side ", a, " is ", c.domain_size[a], " m; expected a positive size");
  }
  int longest = 0;
  for (int a = 1; a < 3; ++a)
    if (c.resolution[a] > c.resolution[longest]) longest = a;
  c.cell_size = c.domain_size[longest] / float(c.resolution[longest]);
  if (bytes.size() >= kFullBytes) {
    c.time_total = field<float>(bytes, kTimeTotal);
    c.cache_id.assign(bytes.data() + kCacheId, strnlen(bytes.data() + kCacheId, 4));
  }
  return c;
}

std::optional<MantaflowVelocityUnits> mantaflow_velocity_units(const std::filesystem::path& data_file, double fps) {
  const auto path = mantaflow_config_path(data_file);
  if (!path) return std::nullopt;
  const MantaflowConfig c = read_mantaflow_config(*path);
  MantaflowVelocityUnits units;
  // The frame length from two consecutive configs (time_total grows by it each frame).
  const std::string digits = frame_digits(data_file.filename().string());
  const long frame = std::stol(digits);
  std::optional<double> frame_length;
  std::string neighbour;
  for (const long other : {frame - 1, frame + 1}) {
    if (other < 0 || frame_length) continue;
    std::string d = std::to_string(other);
    if (d.size() < digits.size()) d.insert(0, digits.size() - d.size(), '0');
    const std::filesystem::path p = config_for(data_file, d);
    if (!c.time_total || !is_file(p)) continue;
    const MantaflowConfig o = read_mantaflow_config(p);
    if (!o.time_total) continue;
    const double length = double(*c.time_total - *o.time_total) / double(frame - other);
    if (length > 0.0 && std::isfinite(length)) frame_length = length, neighbour = p.filename().string();
  }
  if (frame_length) {
    units.frame_rate = kTimeUnitsPerSecond / *frame_length;
    units.frame_length_how = str(*frame_length, " Mantaflow time units a frame (time_total of ", path->filename().string(),
                                 " and ", neighbour, ")");
  }
  const bool fps_implied = fps <= 0.0;
  if (fps_implied) fps = frame_length ? kTimeUnitsPerSecond / *frame_length : 24.0;
  units.fps = fps;
  const double per_frame = frame_length ? *frame_length : kTimeUnitsPerSecond / fps;
  units.factor = float(double(c.cell_size) * per_frame * fps);
  units.how = str("Mantaflow stores velocities in grid cells per Mantaflow time unit; ", path->filename().string(),
                  ": resolution ", c.resolution[0], " x ", c.resolution[1], " x ", c.resolution[2], ", domain ",
                  c.domain_size.x(), " x ", c.domain_size.y(), " x ", c.domain_size.z(), " m, cell ", c.cell_size, " m; ",
                  frame_length ? str("frame length ", per_frame, " time units (time_total of ", path->filename().string(),
                                     " and ", neighbour, ")")
                               : str("frame length 0.1 x 25 / fps = ", per_frame,
                                     " time units (Blender's at time scale 1; no neighbouring config to measure it)"),
                  "; factor = cell x frame length x fps = ", c.cell_size, " x ", per_frame, " x ", fps, " = ", units.factor,
                  fps_implied ? str(" (", fps, " fps: ", frame_length ? "the rate this frame length means" : "assumed",
                                    " at Blender's time scale 1; a run takes its own --fps)")
                              : std::string());
  return units;
}

}  // namespace spume
