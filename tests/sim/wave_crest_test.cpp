// Wave crests at the paper's scale (MODEL.md §1 Eqs. 4-7, §8.10): with its thresholds tau_wc = [2, 8]
// the paper says Eq. 5 alone "would also identify all edges of, e.g., a cube of water as wave crests",
// and that Eq. 7 then keeps only particles moving along their normal. These tests hold spume's crest
// sum to those statements and to sums worked out by hand on shapes whose normals are known exactly.
#include <gtest/gtest.h>

#include <cmath>

#include "sim/diffuse/kernels.h"
#include "sim/diffuse/potentials.h"
#include "tests/support/test_fluids.h"

namespace spume {
namespace {

// Fluid of radius r = 0.01: lattice spacing 2r, support h = 4r (two spacings), volume (2r)^3.
constexpr float kSpacing = 0.02f, kH = 0.04f, kVolume = kSpacing * kSpacing * kSpacing;

DiffuseParams crest_params() {
  DiffuseParams p;
  p.kinetic = {0.1f, 0.3f};            // unit mass at 1 m/s: E = 0.5 J, I_k = 1
  p.wave_crest = {0.0f, 1000.0f};      // I_wc = kappa / 1000: the raw Eq. 5 sum can be read back
  p.k_ta = p.k_wc = 1.0f;
  return p;
}

struct CrestRun {
  std::vector<Vec3f> normals;
  std::vector<float> kappa;  // Eq. 5 after Eqs. 6 and 7 (zero where Eq. 7 fails)
};

// Potentials of `points` moving with `velocity(i, normal_i)`; kappa read back from I_wc.
template <typename Velocity>
CrestRun crest_run(const std::vector<Vec3f>& points, Velocity velocity, DiffuseParams params = crest_params()) {
  auto state = testing::state_of(points, std::vector<Vec3f>(points.size(), Vec3f::Zero()));
  NeighbourGrid grid;
  grid.build(state.positions, kH);
  std::vector<Vec3f> normals;
  compute_normals(grid, kVolume, params, nullptr, normals);
  for (size_t i = 0; i < points.size(); ++i) state.velocities[i] = state.motion[i] = velocity(i, normals[i]);
  FormationPotentials out;
  compute_potentials(grid, state, params, kVolume, nullptr, out);
  CrestRun run{out.normals, std::vector<float>(points.size())};
  for (size_t i = 0; i < points.size(); ++i) run.kappa[i] = out.wave_crest[i] * params.wave_crest.hi;
  return run;
}

// Every particle moves along its own normal at 1 m/s, so Eq. 7 passes wherever there is a normal and
// the crest potential is Eq. 5 alone.
const auto along_normal = [](size_t, const Vec3f& n) { return n.squaredNorm() > 0 ? n : Vec3f(0, 1, 0); };

// A cube of n^3 lattice particles; `where` counts the coordinates on the cube's boundary (1 face,
// 2 edge, 3 corner) and `from_edge` the lattice steps to the nearest edge for face particles.
struct Cube {
  std::vector<Vec3f> points;
  std::vector<int> where, from_edge;
};
Cube lattice_cube(int n, float jitter) {
  Cube c;
  c.points = testing::lattice(Vec3f::Zero(), Vec3f::Constant((n - 1) * kSpacing), kSpacing);
  for (const Vec3f& p : c.points) {
    int boundary = 0, second_smallest = n, smallest = n;
    for (int a = 0; a < 3; ++a) {
      const int k = int(std::lround(p[a] / kSpacing)), depth = std::min(k, n - 1 - k);
      boundary += depth == 0;
      if (depth < smallest) second_smallest = smallest, smallest = depth;
      else second_smallest = std::min(second_smallest, depth);
    }
    c.where.push_back(boundary);
    c.from_edge.push_back(second_smallest);
  }
  if (jitter > 0) testing::jitter(c.points, jitter * kSpacing, 11);
  return c;
}

void expect_edges_and_corners_are_crests_and_faces_are_not(float jitter) {
  const Cube cube = lattice_cube(12, jitter);
  const CrestRun run = crest_run(cube.points, along_normal);
  const float tau_wc_min = 2.0f;  // the paper's threshold (section 4)
  int edges = 0, corners = 0, faces = 0;
  for (size_t i = 0; i < cube.points.size(); ++i) {
    if (cube.where[i] >= 2) {
      EXPECT_GE(run.kappa[i], tau_wc_min) << (cube.where[i] == 3 ? "corner " : "edge ") << i;
      (cube.where[i] == 3 ? corners : edges)++;
    }
    // A face particle farther than the crest support (2 h, four steps) from every edge sees a flat
    // surface: Eq. 6 keeps no neighbour, or (jittered) only ones whose normals barely differ.
    if (cube.where[i] == 1 && cube.from_edge[i] >= 4) {
      EXPECT_LT(run.kappa[i], tau_wc_min) << "face " << i;
      ++faces;
    }
  }
  EXPECT_EQ(corners, 8);
  EXPECT_EQ(edges, 12 * 10);
  EXPECT_EQ(faces, 6 * 4 * 4);
}

TEST(WaveCrestScale, EquationFiveAloneFlagsTheEdgesAndCornersOfACubeButNotItsFaces) {
  expect_edges_and_corners_are_crests_and_faces_are_not(0.0f);
}

TEST(WaveCrestScale, AJitteredCubeToo) { expect_edges_and_corners_are_crests_and_faces_are_not(0.1f); }

TEST(WaveCrestScale, SummedOverOneSupportRadiusTheEdgesNeverReachThePapersThreshold) {
  // Why the crest sum reaches 2 h (diffuse.crest_support): over h only the outermost layer has a
  // normal and an edge particle's sum stays near 0.6 (MODEL.md §8.10), below tau_wc,min = 2.
  DiffuseParams narrow = crest_params();
  narrow.crest_support = 1.0f;
  const Cube cube = lattice_cube(12, 0.0f);
  const CrestRun run = crest_run(cube.points, along_normal, narrow);
  for (size_t i = 0; i < cube.points.size(); ++i)
    if (cube.where[i] >= 2) {
      EXPECT_LT(run.kappa[i], 1.0f) << i;
    }
}

TEST(WaveCrestMotion, ACubeAtRestFormsNoCrest) {
  const Cube cube = lattice_cube(10, 0.0f);
  const CrestRun run = crest_run(cube.points, [](size_t, const Vec3f&) { return Vec3f::Zero(); });
  for (float k : run.kappa) ASSERT_EQ(k, 0.0f);
}

TEST(WaveCrestMotion, ACubeSlidingSidewaysKeepsOnlyItsLeadingEdges) {
  // Sliding along +x at 1 m/s. By symmetry an edge particle's normal is the diagonal of its two faces
  // and a corner's the diagonal of three: cos = 1/sqrt(2) = 0.71 >= 0.6 for the four edges at x max,
  // 0 or less for the trailing edges and those parallel to x, and 1/sqrt(3) = 0.58 < 0.6 for the
  // leading corners. So Eq. 7 keeps the four leading edges (their Eq. 5 sum is above 2) and nothing else
  // of the cube's edges and corners.
  const int n = 10;
  const Cube cube = lattice_cube(n, 0.0f);
  const CrestRun run = crest_run(cube.points, [](size_t, const Vec3f&) { return Vec3f(1, 0, 0); });
  const float x_max = (n - 1) * kSpacing;
  int leading = 0;
  for (size_t i = 0; i < cube.points.size(); ++i) {
    if (cube.where[i] < 2) continue;
    const bool at_front = std::abs(cube.points[i].x() - x_max) < 1e-6f;
    if (cube.where[i] == 2 && at_front) {
      EXPECT_GE(run.kappa[i], 2.0f) << i;
      ++leading;
    } else {
      EXPECT_EQ(run.kappa[i], 0.0f) << (cube.where[i] == 3 ? "corner " : "edge ") << i;
    }
  }
  EXPECT_EQ(leading, 4 * (n - 2));
}

// Two parallel lattice layers one spacing apart (a thin jet sheet), n x n particles each, in y = 0 and
// y = spacing.
std::vector<Vec3f> sheet(int n) {
  return testing::lattice(Vec3f::Zero(), Vec3f((n - 1) * kSpacing, kSpacing, (n - 1) * kSpacing), kSpacing);
}

TEST(WaveCrestMotion, AFlatSheetMovingInItsPlaneFormsNoCrest) {
  const auto points = sheet(16);
  const CrestRun run = crest_run(points, [](size_t, const Vec3f&) { return Vec3f(0.8f, 0, 0.6f); });
  // Only the sheet's rim has normals with an in-plane part; its middle moves at right angles to them.
  for (size_t i = 0; i < points.size(); ++i) {
    const Vec3f& p = points[i];
    if (p.x() > 0.1f && p.x() < 0.2f && p.z() > 0.1f && p.z() < 0.2f) {
      ASSERT_EQ(run.kappa[i], 0.0f) << i;
    }
  }
}

TEST(WaveCrestMotion, AFlatSheetMovingAlongItsNormalFormsCrestsOnItsLeadingFace) {
  // Away from the rim the normals are exactly +y (top layer) and -y (bottom) by symmetry. For a top
  // particle, Eq. 6 keeps the bottom layer only (the top layer lies level with it, x^_ji . n = 0), each
  // bottom particle at lateral offset (a, b) steps contributing (1 - (-1)) (1 - d / 2h) with
  // d = spacing sqrt(1 + a^2 + b^2). The bottom layer moves against its normal: Eq. 7 removes it.
  const int n = 20;
  const auto points = sheet(n);
  const CrestRun run = crest_run(points, [](size_t, const Vec3f&) { return Vec3f(0, 1, 0); });
  double expected = 0;
  for (int a = -4; a <= 4; ++a)
    for (int b = -4; b <= 4; ++b) {
      const double d = std::sqrt(1.0 + a * a + b * b) * kSpacing;
      if (d <= 2 * kH) expected += 2.0 * (1.0 - d / (2 * kH));
    }
  int checked = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    const Vec3f& p = points[i];
    const bool middle = p.x() > 0.11f && p.x() < 0.27f && p.z() > 0.11f && p.z() < 0.27f;
    if (!middle) continue;
    if (p.y() > 0.5f * kSpacing) {
      EXPECT_NEAR(run.kappa[i], expected, 1e-3 * expected) << i;
      ++checked;
    } else {
      EXPECT_EQ(run.kappa[i], 0.0f) << i;
    }
  }
  EXPECT_GT(checked, 30);
}

// A horizontal cylinder of water (convex) or a cylindrical channel in a block (concave), radius
// `radius` lattice steps, axis along z, built from concentric shells of evenly spaced particles (a
// smooth surface; a lattice circle's staircase is full of small corners).
std::vector<Vec3f> cylinder(float radius, bool convex, int length = 16) {
  std::vector<Vec3f> points;
  for (int shell = 0; shell < 5; ++shell) {
    const float rho = convex ? radius - shell : radius + shell;
    if (rho < 0.5f) {
      for (int k = 0; k < length; ++k) points.emplace_back(0.0f, 0.0f, k * kSpacing);
      break;
    }
    const int around = int(std::lround(2 * M_PI * rho));
    for (int j = 0; j < around; ++j) {
      const double angle = 2 * M_PI * (j + 0.5 * (shell % 2)) / around;
      for (int k = 0; k < length; ++k)
        points.emplace_back(float(rho * std::cos(angle)) * kSpacing, float(rho * std::sin(angle)) * kSpacing,
                            k * kSpacing);
    }
  }
  if (!convex) {  // the block around the shells, on the lattice
    const int half = int(radius) + 9;
    for (int x = -half; x <= half; ++x)
      for (int y = -half; y <= half; ++y)
        if (std::hypot(float(x), float(y)) > radius + 4.5f)
          for (int k = 0; k < length; ++k) points.emplace_back(x * kSpacing, y * kSpacing, k * kSpacing);
  }
  return points;
}

// Raw Eq. 5 on the top of the cylinder's surface (the crest of a rising roll, or the bottom of a
// rising channel), more than 2 h from its open ends, with everything moving up at 1 m/s: the least
// and the largest value there.
std::pair<float, float> crest_on_top(float radius, bool convex) {
  const auto points = cylinder(radius, convex);
  const CrestRun run = crest_run(points, [](size_t, const Vec3f&) { return Vec3f(0, 1, 0); });
  float lowest = 1e9f, highest = 0.0f;
  int count = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    const Vec3f& p = points[i];
    const float rho = std::hypot(p.x(), p.y()) / kSpacing, steps_along = p.z() / kSpacing;
    const bool top = convex ? p.y() > 0 : p.y() < 0;  // where the outward normal points up
    if (std::abs(rho - radius) < 0.25f && top && std::abs(p.x()) < 0.5f * radius * kSpacing && steps_along > 5.5f &&
        steps_along < 10.5f)
      lowest = std::min(lowest, run.kappa[i]), highest = std::max(highest, run.kappa[i]), ++count;
  }
  EXPECT_GT(count, 3);
  return {lowest, highest};
}

TEST(WaveCrestShape, ASharpRollRisingAlongItsNormalIsACrest) {
  // Radius two lattice steps (4r): the normals of the surface neighbours within 2 h turn by up to
  // 90 degrees, as on a cube's edge.
  EXPECT_GE(crest_on_top(2.0f, true).first, 2.0f);
}

TEST(WaveCrestShape, TheSameChannelRisingIsNoCrest) {
  // Concave: every surface neighbour lies in front of the particle's normal (Eq. 6).
  EXPECT_EQ(crest_on_top(2.0f, false).second, 0.0f);
}

TEST(WaveCrestShape, AGentleRollIsNoCrest) {
  // Radius six steps: within 2 h the normals turn by at most 4/6 rad, and only the few neighbours
  // that far out turn that much; Eq. 5 stays below 2.
  EXPECT_LT(crest_on_top(6.0f, true).second, 2.0f);
}

}  // namespace
}  // namespace spume
