#include "sim/geometry/body_track.h"

#include <algorithm>
#include <cmath>

#include "sim/core/error.h"

namespace spume {

std::vector<BodyPose> BodyTrack::at_time(double t) const {
  if (frames.empty()) return {};
  const double x = t * fps - double(first_frame);
  if (!(x > 0.0)) return frames.front();
  if (x >= double(frames.size() - 1)) return frames.back();
  const size_t k = size_t(std::floor(x));
  const float w = float(x - double(k));
  std::vector<BodyPose> out = frames[k];
  const std::vector<BodyPose>& next = frames[k + 1];
  for (size_t i = 0; i < out.size(); ++i) {
    BodyPose& p = out[i];
    const BodyPose& q = next[i];
    p.position += w * (q.position - p.position);
    p.orientation = p.orientation.slerp(w, q.orientation);
    p.velocity += w * (q.velocity - p.velocity);
    p.angular_velocity += w * (q.angular_velocity - p.angular_velocity);
  }
  return out;
}

void BodyTrack::validate(const std::string& source) const {
  if (!(fps > 0.0) || !std::isfinite(fps)) fail(source, ": body track fps must be positive, found ", fps);
  for (size_t k = 1; k < frames.size(); ++k) {
    bool same = frames[k].size() == frames[0].size();
    for (size_t i = 0; same && i < frames[k].size(); ++i) same = frames[k][i].solid == frames[0][i].solid;
    if (!same) fail(source, ": frame ", first_frame + int(k), " lists other bodies than frame ", first_frame);
  }
}

SolidSet solids_at_time(const SolidSet& solids, const BodyTrack& track, double t) {
  SolidSet moved = solids.at_time(t);
  if (track.empty()) return moved;
  return moved.posed(track.at_time(t));
}

}  // namespace spume
