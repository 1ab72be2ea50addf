#include "sim/io/vdb_points_writer.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <mutex>
#include <sstream>

#include <openvdb/openvdb.h>
#include <openvdb/io/Stream.h>
#include <openvdb/points/PointConversion.h>
#include <openvdb/points/PointDataGrid.h>
#include <openvdb/points/PointGroup.h>

#include "sim/core/atomic_file.h"
#include "sim/core/error.h"

namespace spume {
namespace {

namespace vp = openvdb::points;
using PositionCodec = vp::FixedPointCodec</*OneByte=*/false, vp::PositionRange>;  // 16 bits per axis
constexpr double kPositionSteps = 65535.0;  // steps across one voxel
constexpr float kHalfMax = 65504.0f;

void initialize_openvdb() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

// Positions for OpenVDB's partitioner and codec, in double, moved up by half a fixed-point step: the
// codec truncates to the step below, so the shift makes it round to the nearest step instead.
class ShiftedPositions {
 public:
  using value_type = openvdb::Vec3d;
  using PosType = openvdb::Vec3d;
  ShiftedPositions(const std::vector<Vec3f>& positions, double shift) : positions_(positions), shift_(shift) {}
  size_t size() const { return positions_.size(); }
  void getPos(size_t n, openvdb::Vec3d& xyz) const {
    const Vec3f& p = positions_[n];
    xyz = openvdb::Vec3d(double(p.x()) + shift_, double(p.y()) + shift_, double(p.z()) + shift_);
  }

 private:
  const std::vector<Vec3f>& positions_;
  double shift_;
};

template <typename T>
void add_attribute(vp::PointDataTree& tree, const openvdb::tools::PointIndexTree& index, const char* name,
                   const std::vector<T>& values) {
  vp::populateAttribute<vp::PointDataTree, openvdb::tools::PointIndexTree, vp::PointAttributeVector<T>>(
      tree, index, name, vp::PointAttributeVector<T>(values));
}

bool is_hex(char c) { return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F'); }

// FNV-1a 64 of bytes, seeded.
uint64_t fnv1a(const std::string& bytes, size_t from, uint64_t seed) {
  uint64_t h = seed;
  for (size_t i = from; i < bytes.size(); ++i) h = (h ^ uint8_t(bytes[i])) * 1099511628211ull;
  return h;
}

// OpenVDB's header: magic (8 bytes), file version, library major and minor (4 each), a has-offsets
// byte, then the UUID as 36 characters (8-4-4-4-12 hex digits).
constexpr size_t kUuidOffset = 21, kUuidLength = 36;

void replace_uuid_with_digest(std::string& bytes) {
  if (bytes.size() < kUuidOffset + kUuidLength) fail("OpenVDB wrote a header of ", bytes.size(), " bytes only");
  for (size_t i = 0; i < kUuidLength; ++i) {
    const char c = bytes[kUuidOffset + i];
    const bool dash = i == 8 || i == 13 || i == 18 || i == 23;
    if (dash ? c != '-' : !is_hex(c))
      fail("OpenVDB's header has no UUID where spume expects it (byte ", kUuidOffset, "): an OpenVDB version "
           "spume does not know");
  }
  const size_t rest = kUuidOffset + kUuidLength;
  const uint64_t a = fnv1a(bytes, rest, 14695981039346656037ull), b = fnv1a(bytes, rest, 0x9e3779b97f4a7c15ull);
  char uuid[kUuidLength + 1];
  std::snprintf(uuid, sizeof uuid, "%08x-%04x-%04x-%04x-%012llx", unsigned(a >> 32), unsigned(a >> 16) & 0xffffu,
                unsigned(a) & 0xffffu, unsigned(b >> 48), static_cast<unsigned long long>(b & 0xffffffffffffull));
  bytes.replace(kUuidOffset, kUuidLength, uuid, kUuidLength);
}

}  // namespace

std::string vdb_points_format(float voxel_size) {
  // Bump the layout number when the attributes, codecs or metadata written here change.
  return str("spume-vdb-points 1, OpenVDB ", OPENVDB_LIBRARY_VERSION_STRING, ", voxel ", voxel_size);
}

float vdb_points_voxel_size(float particle_radius) { return 2.0f * particle_radius; }

double vdb_position_error(float voxel_size, float coordinate) {
  const double step = double(voxel_size) / kPositionSteps;
  const double ulp = std::nextafter(std::fabs(coordinate), std::numeric_limits<float>::infinity()) - std::fabs(coordinate);
  // Half a step, with 4% for the codec's own float arithmetic (it scales a float offset by 65535),
  // and half an ulp for a reader that holds the world position as a float.
  return 0.52 * step + 0.5 * ulp;
}

double vdb_velocity_error(float component) {
  return std::max(std::ldexp(std::fabs(double(component)), -11), std::ldexp(1.0, -25));
}

std::string vdb_points_bytes(const DiffuseFrame& frame, float voxel_size, std::span<const float> ages) {
  if (!ages.empty() && ages.size() != frame.size()) fail("OpenVDB points: ", ages.size(), " ages for ", frame.size(), " particles");
  if (!(voxel_size > 0.0f) || !std::isfinite(voxel_size)) fail("OpenVDB points: voxel size ", voxel_size, " is not positive");
  initialize_openvdb();
  const size_t n = frame.size();
  const openvdb::math::Transform::Ptr transform = openvdb::math::Transform::createLinearTransform(voxel_size);
  const ShiftedPositions positions(frame.positions, 0.5 * double(voxel_size) / kPositionSteps);
  const openvdb::tools::PointIndexGrid::Ptr index =
      openvdb::tools::createPointIndexGrid<openvdb::tools::PointIndexGrid>(positions, *transform);
  const vp::PointDataGrid::Ptr grid =
      vp::createPointDataGrid<PositionCodec, vp::PointDataGrid>(*index, positions, *transform);
  grid->setName("points");
  vp::PointDataTree& tree = grid->tree();

  std::vector<openvdb::Vec3f> velocities(n);
  std::vector<int64_t> ids(n);
  std::vector<int32_t> types(n);
  for (size_t i = 0; i < n; ++i) {
    const Vec3f& v = frame.velocities[i];
    if (!(std::fabs(v.x()) <= kHalfMax && std::fabs(v.y()) <= kHalfMax && std::fabs(v.z()) <= kHalfMax))
      fail("OpenVDB points: diffuse particle ", frame.ids[i], " moves at (", v.x(), ", ", v.y(), ", ", v.z(),
           ") m/s, beyond the 65504 m/s a half-float velocity holds");
    velocities[i] = openvdb::Vec3f(v.x(), v.y(), v.z());
    ids[i] = int64_t(frame.ids[i]);  // the id's 64 bits: negative from parent ids of 2^31 up (frames.h)
    types[i] = int32_t(frame.types[i]);
  }
  if (n > 0) {
    vp::appendAttribute(tree, "v", vp::TypedAttributeArray<openvdb::Vec3f, vp::TruncateCodec>::attributeType());
    add_attribute(tree, index->tree(), "v", velocities);
    vp::appendAttribute<float>(tree, "lifetime");
    add_attribute(tree, index->tree(), "lifetime", frame.lifetimes);
    if (!ages.empty()) {  // Houdini's names: age since birth, life the whole span (alive while age < life)
      std::vector<float> age(ages.begin(), ages.end()), life(n);
      for (size_t i = 0; i < n; ++i) life[i] = age[i] + frame.lifetimes[i];
      vp::appendAttribute<float>(tree, "age");
      add_attribute(tree, index->tree(), "age", age);
      vp::appendAttribute<float>(tree, "life");
      add_attribute(tree, index->tree(), "life", life);
    }
    vp::appendAttribute<int64_t>(tree, "id");
    add_attribute(tree, index->tree(), "id", ids);
    vp::appendAttribute<int32_t>(tree, "type");
    add_attribute(tree, index->tree(), "type", types);
    for (int t = 0; t < kDiffuseTypeCount; ++t) {
      const char* group = to_string(DiffuseType(t));
      std::vector<short> member(n);
      for (size_t i = 0; i < n; ++i) member[i] = types[i] == t ? 1 : 0;
      vp::appendGroup(tree, group);
      vp::setGroup(tree, index->tree(), member, group);
    }
  }
  grid->insertMeta("frame", openvdb::Int32Metadata(frame.index));
  grid->insertMeta("time", openvdb::DoubleMetadata(frame.time));

  std::ostringstream out(std::ios::binary);
  openvdb::io::Stream stream(out);
  stream.setCompression(openvdb::io::COMPRESS_BLOSC | openvdb::io::COMPRESS_ACTIVE_MASK);
  openvdb::GridCPtrVec grids{grid};
  openvdb::MetaMap file_meta;
  file_meta.insertMeta("creator", openvdb::StringMetadata("spume"));
  stream.write(grids, file_meta);
  std::string bytes = std::move(out).str();
  replace_uuid_with_digest(bytes);
  return bytes;
}

void write_vdb_points(const std::filesystem::path& path, const DiffuseFrame& frame, float voxel_size,
                      std::span<const float> ages) {
  const std::string bytes = with_context(path.string(), [&] { return vdb_points_bytes(frame, voxel_size, ages); });
  write_file_atomically(path, [&](std::ostream& out) { out.write(bytes.data(), std::streamsize(bytes.size())); });
}

}  // namespace spume
