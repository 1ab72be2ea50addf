#pragma once
// What a fluid sequence holds, frame by frame, without keeping the frames: each input file's identity,
// its particle count and bounds, and how many particles press against each side of those bounds.
// The whole sequence's domain and camera, the container inferred from it, the inputs' part of the
// caches' fingerprints and the spacing check all read this one pass. It is kept beside the outputs
// (OUT/<scene>/fluid_survey.json): a rerun surveys again only the files whose identity changed. Each
// entry carries a digest of its identity and measures; an entry that does not match it (edited by
// hand) is not trusted: its frame is surveyed again, and the survey's notes say so.
#include <array>
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "sim/core/vec.h"
#include "sim/io/file_identity.h"
#include "sim/io/fluid_read_options.h"

namespace spume {

struct FrameSurvey {
  int frame = 0;
  FileIdentity file;
  uint64_t particles = 0;
  Aabb bounds;
  // Per side (-x, +x, -y, +y, -z, +z), the coordinate of the 4th outermost particle (with fewer
  // particles, the innermost; NaN in an empty frame): where the fluid presses against something
  // flat, a sheet sits there; a few stray particles do not move it.
  std::array<float, 6> sheet{};
  Vec3f centroid = Vec3f::Zero();  // the particles' mean position (NaN in an empty frame)
  // The particles' mean stored velocity, as the file holds it (NaN without velocities): over a frame
  // interval it should match the centroid's motion (check_stored_velocities).
  Vec3f mean_velocity = Vec3f::Constant(NAN);
  // The fluid's top and bottom in columns (with stored velocities only): the columns are squares of
  // side `column` (a power of two in metres, about an eighth of the frame's largest extent, aligned to
  // multiples of it, so consecutive frames of a similar size share them) across y, spume's up axis
  // (the axis turned up by fluid.up_axis). Per side (-y, +y) and column holding 4 particles or more: the
  // 4th outermost coordinate, and the mean stored velocity along y of the 8 outermost. Where such an
  // extreme is a free surface it moves with the fluid there, whatever particles are added or removed
  // elsewhere (check_stored_velocities reads the side facing up; the x and z sides are walls or a
  // narrow band's inner edge in the caches this is for, so they are not surveyed).
  struct ColumnFront {
    int side = 0;  // 2: -y, 3: +y (the numbering of the six sides -x, +x, -y, +y, -z, +z)
    int i = 0, j = 0;  // the column's index along the side's other two axes (in x, y, z order)
    float sheet = 0.0f, velocity = 0.0f;
  };
  float column = 0.0f;
  std::vector<ColumnFront> fronts;
  // With ids and stored velocities: the particles whose ids hash lowest (up to 64), the same ones in
  // every frame they are in, so consecutive frames compare each one's motion with its stored velocity
  // whatever the count does.
  struct Tracked {
    uint32_t id = 0;
    Vec3f position = Vec3f::Zero(), velocity = Vec3f::Zero();
  };
  std::vector<Tracked> tracked;
  bool has_mean_velocity() const { return std::isfinite(mean_velocity.x()); }
  bool has_sheet() const { return particles >= 4; }  // a sheet of 4 particles, not strays
};

struct FluidSurvey {
  std::string pattern;
  FluidReadOptions read;            // how its files were read (axis, VDB grid): read them again the same way
  std::vector<FrameSurvey> frames;  // in frame order
  // Median distance from a particle to its nearest neighbour in the first frame holding two or more
  // (a sample of up to 512 particles): the cache's particle spacing, to check the radius against.
  float spacing = 0.0f;
  Aabb bounds() const;            // union over every frame (empty frames add nothing)
  std::vector<std::string> notes;  // what the log should say (kept entries that were not trusted)
};

// Surveys `frames` of `pattern` (they must exist), reusing what `keep` records for files whose
// identity is unchanged, and rewrites `keep` (atomically) when anything was surveyed. `keep` may be
// empty: nothing is read or written. Frames are read in parallel. Progress on stderr unless quiet.
// Files are read with `read` (a survey kept under other options is not reused).
FluidSurvey survey_fluid_files(const std::string& pattern, const std::vector<int>& frames,
                               const std::filesystem::path& keep, bool quiet, const FluidReadOptions& read = {});

// One frame's entry from particle positions and stored velocities, if any (exposed for tests); no
// particles: empty bounds, NaN sheets.
FrameSurvey survey_positions(const std::vector<Vec3f>& positions, const std::vector<Vec3f>& velocities = {},
                             const std::vector<uint32_t>& ids = {});
// Median nearest-neighbour distance over up to `samples` evenly strided particles.
float median_spacing(const std::vector<Vec3f>& positions, size_t samples = 512);

}  // namespace spume
