#include "sim/stage/body_track_file.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "sim/core/atomic_file.h"
#include "sim/core/error.h"

namespace spume {
namespace {

constexpr const char* kHeader = "frame,solid,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz";
constexpr int kColumns = 15;

void write_row(std::ostream& out, int frame, const BodyPose& p) {
  char buffer[512];
  const Vec3f& x = p.position;
  const Quatf& q = p.orientation;
  const Vec3f& v = p.velocity;
  const Vec3f& w = p.angular_velocity;
  std::snprintf(buffer, sizeof buffer, "%d,%u,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n",
                frame, p.solid, x.x(), x.y(), x.z(), q.w(), q.x(), q.y(), q.z(), v.x(), v.y(), v.z(), w.x(), w.y(),
                w.z());
  out << buffer;
}

// The row's 15 numbers, or an Error naming the file, line and column.
std::vector<double> parse_row(const std::string& line, const std::string& where) {
  std::vector<double> values;
  const char* p = line.c_str();
  while (true) {
    char* end = nullptr;
    errno = 0;
    const double value = std::strtod(p, &end);
    if (end == p || errno == ERANGE || !std::isfinite(value))
      fail(where, ": column ", values.size() + 1, " is not a finite number (expected ", kHeader, ")");
    values.push_back(value);
    p = end;
    if (*p == '\0' || *p == '\r') break;
    if (*p != ',') fail(where, ": unexpected '", *p, "' after column ", values.size());
    ++p;
  }
  if (int(values.size()) != kColumns) fail(where, ": ", values.size(), " columns, expected ", kColumns, " (", kHeader, ")");
  return values;
}

}  // namespace

void write_body_track(const std::filesystem::path& path, const BodyTrack& track) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << kHeader << '\n';
    for (size_t k = 0; k < track.frames.size(); ++k)
      for (const BodyPose& p : track.frames[k]) write_row(out, track.first_frame + int(k), p);
  });
}

BodyTrack read_body_track(const std::filesystem::path& path, double fps) {
  std::ifstream in(path);
  if (!in) fail(path.string(), ": cannot open the body track");
  std::string line;
  if (!std::getline(in, line) || line.rfind(kHeader, 0) != 0)
    fail(path.string(), ": line 1: expected the header ", kHeader);
  BodyTrack track;
  track.fps = fps;
  int line_number = 1;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.empty()) continue;
    const std::string where = str(path.string(), ": line ", line_number);
    const std::vector<double> v = parse_row(line, where);
    const int frame = int(v[0]);
    if (double(frame) != v[0] || v[1] < 0 || double(uint32_t(v[1])) != v[1])
      fail(where, ": frame and solid must be whole numbers >= 0");
    if (track.frames.empty()) track.first_frame = frame;
    const int k = frame - track.first_frame;
    if (k == int(track.frames.size())) track.frames.emplace_back();
    if (k != int(track.frames.size()) - 1)
      fail(where, ": frame ", frame, " out of order (frames must run consecutively from ", track.first_frame, ")");
    BodyPose p;
    p.solid = uint32_t(v[1]);
    p.position = Vec3f(float(v[2]), float(v[3]), float(v[4]));
    p.orientation = Quatf(float(v[5]), float(v[6]), float(v[7]), float(v[8]));
    if (std::abs(p.orientation.norm() - 1.0f) > 1e-3f) fail(where, ": orientation is not a unit quaternion");
    p.velocity = Vec3f(float(v[9]), float(v[10]), float(v[11]));
    p.angular_velocity = Vec3f(float(v[12]), float(v[13]), float(v[14]));
    track.frames.back().push_back(p);
  }
  if (track.frames.empty()) fail(path.string(), ": the body track has no rows");
  track.validate(path.string());
  return track;
}

BodyTrack scene_body_track(const SimScene& scene, const std::filesystem::path& scene_out) {
  if (!scene.solids.any_dynamic()) return {};
  if (scene.source != FluidSourceKind::Solver)
    fail(scene.name, ": /solids: dynamic solids are moved by spume's fluid solver; with fluid.source \"files\" "
         "give them a \"motion\" or make them static");
  const std::filesystem::path path = body_track_path(scene_out);
  if (!std::filesystem::is_regular_file(path))
    fail(path.string(), ": no body track for the scene's dynamic solids; run `spume simulate` first");
  BodyTrack track = read_body_track(path, scene.fluid.fps);
  for (const BodyPose& p : track.frames.front())
    if (p.solid >= scene.solids.solids().size() || !scene.solids.solids()[p.solid].dynamics.enabled)
      fail(path.string(), ": solid ", p.solid, " is not a dynamic solid of scene ", scene.name);
  return track;
}

}  // namespace spume
