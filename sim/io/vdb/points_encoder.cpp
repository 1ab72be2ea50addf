#include "sim/io/vdb/openvdb_io.h"
#include "sim/io/vdb_points_writer.h"

#include <cmath>
#include <limits>

#include <openvdb/openvdb.h>
#include <openvdb/points/PointConversion.h>
#include <openvdb/points/PointDataGrid.h>
#include <openvdb/points/PointGroup.h>

#include "sim/core/error.h"
#include "sim/io/vdb/file_bytes.h"

namespace spume::openvdb_io {
namespace {

namespace vp = openvdb::points;
using PositionCodec = vp::FixedPointCodec</*OneByte=*/false, vp::PositionRange>;  // 16 bits per axis
constexpr float kHalfMax = 65504.0f;

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

}  // namespace

std::string points_bytes(const DiffuseFrame& frame, float voxel_size, std::span<const float> ages) {
  if (!ages.empty() && ages.size() != frame.size()) fail("OpenVDB points: ", ages.size(), " ages for ", frame.size(), " particles");
  if (!(voxel_size > 0.0f) || !std::isfinite(voxel_size)) fail("OpenVDB points: voxel size ", voxel_size, " is not positive");
  initialize_openvdb();
  const size_t n = frame.size();
  const openvdb::math::Transform::Ptr transform = openvdb::math::Transform::createLinearTransform(voxel_size);
  const ShiftedPositions positions(frame.positions, 0.5 * double(voxel_size) / kVdbPositionSteps);
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

  return vdb_file_bytes({grid});
}

}  // namespace spume::openvdb_io
