#include "sim/io/vdb/openvdb_io.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <fstream>
#include <optional>

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/points/AttributeArray.h>
#include <openvdb/points/PointCount.h>
#include <openvdb/points/PointDataGrid.h>

#include "sim/core/error.h"
#include "sim/core/out_of_memory.h"
#include "sim/io/attribute_names.h"
#include "sim/io/contained_read.h"
#include "sim/io/vdb/file_bytes.h"

namespace spume::openvdb_io {
namespace {

namespace vdb = openvdb;
namespace vpts = openvdb::points;

// The value type and codec of attribute `index`, e.g. ("vec3s", "trnc").
std::pair<std::string, std::string> attribute_type(const vpts::AttributeSet::Descriptor& d, size_t index) {
  const vdb::NamePair& t = d.type(index);
  return {t.first, t.second};
}

std::optional<size_t> find_attribute(const vpts::AttributeSet::Descriptor& d, std::string_view name) {
  const size_t i = d.find(std::string(name));
  if (i == vpts::AttributeSet::INVALID_POS) return std::nullopt;
  return i;
}

// Reads a 3-vector attribute of either float precision, whatever its codec.
template <typename Leaf>
Vec3f vec3_at(const Leaf& leaf, size_t index, vdb::Index i, bool doubles) {
  if (doubles) {
    const vpts::AttributeHandle<vdb::Vec3d> h(leaf.constAttributeArray(index));
    const vdb::Vec3d v = h.get(i);
    return Vec3f(float(v.x()), float(v.y()), float(v.z()));
  }
  const vpts::AttributeHandle<vdb::Vec3f> h(leaf.constAttributeArray(index));
  const vdb::Vec3f v = h.get(i);
  return Vec3f(v.x(), v.y(), v.z());
}

bool is_vec3(const std::string& type, bool& doubles) {
  doubles = type == "vec3d";
  return type == "vec3s" || type == "vec3d";
}

struct GridRead {
  std::vector<Vec3f> positions, velocities;
  std::vector<int64_t> ids;
  std::vector<float> masses;
  std::string velocity_name, id_name, mass_name;
  // spume's diffuse export (io/vdb_points_writer.h): `lifetime` (float) and `type` (int32) as well.
  bool diffuse = false;
  std::vector<float> lifetimes;
  std::vector<int32_t> types;
  std::vector<float> ages;  // Houdini's `age`, when the export carries it
};

GridRead read_point_grid(const vpts::PointDataGrid& grid, const std::string& where) {
  GridRead out;
  const auto first = grid.tree().cbeginLeaf();
  if (!first) return out;
  const vpts::AttributeSet::Descriptor& d = first->attributeSet().descriptor();
  const auto p = find_attribute(d, "P");
  if (!p) fail(where, ": point grid '", grid.getName(), "' has no position attribute P");
  bool p_doubles = false;
  if (!is_vec3(attribute_type(d, *p).first, p_doubles))
    fail(where, ": point grid '", grid.getName(), "': P is ", attribute_type(d, *p).first, "; expected vec3s or vec3d");
  std::optional<size_t> v;
  bool v_doubles = false;
  for (const std::string_view name : io::attribute_names(io::AttributeRole::Velocity))
    if ((v = find_attribute(d, name))) {
      out.velocity_name = name;
      if (!is_vec3(attribute_type(d, *v).first, v_doubles))
        fail(where, ": point grid '", grid.getName(), "': velocity attribute '", name, "' is ",
             attribute_type(d, *v).first, "; expected vec3s or vec3d");
      break;
    }
  std::optional<size_t> id;
  bool id64 = false;
  for (const std::string_view name : io::attribute_names(io::AttributeRole::Id))
    if ((id = find_attribute(d, name))) {
      const std::string type = attribute_type(d, *id).first;
      if (type != "int32" && type != "int64")
        fail(where, ": point grid '", grid.getName(), "': ", name, " is ", type, "; the particle id must be int32 or int64");
      id64 = type == "int64";
      out.id_name = name;
      break;
    }
  std::optional<size_t> mass;
  for (const std::string_view name : io::attribute_names(io::AttributeRole::Mass))
    if ((mass = find_attribute(d, name))) {
      if (attribute_type(d, *mass).first != "float")
        fail(where, ": point grid '", grid.getName(), "': ", name, " is ", attribute_type(d, *mass).first,
             "; the mass must be float");
      out.mass_name = name;
      break;
    }

  const auto lifetime = find_attribute(d, "lifetime"), type = find_attribute(d, "type");
  out.diffuse = lifetime && type && attribute_type(d, *lifetime).first == "float" &&
                attribute_type(d, *type).first == "int32";
  auto age = find_attribute(d, "age");
  if (!out.diffuse || (age && attribute_type(d, *age).first != "float")) age.reset();

  const vdb::math::Transform& xform = grid.transform();
  for (auto leaf = grid.tree().cbeginLeaf(); leaf; ++leaf) {
    // Every leaf of a grid normally shares one descriptor; one that does not would misread silently.
    if (leaf->attributeSet().descriptor().find("P") != *p)
      fail(where, ": point grid '", grid.getName(), "': its leaves disagree on their attributes");
    for (auto i = leaf->beginIndexAll(); i; ++i) {
      const Vec3f local = vec3_at(*leaf, *p, *i, p_doubles);
      const vdb::Vec3d index_space = i.getCoord().asVec3d() + vdb::Vec3d(local.x(), local.y(), local.z());
      const vdb::Vec3d world = xform.indexToWorld(index_space);
      out.positions.emplace_back(float(world.x()), float(world.y()), float(world.z()));
      if (v) out.velocities.push_back(vec3_at(*leaf, *v, *i, v_doubles));
      if (id) {
        if (id64) {
          out.ids.push_back(vpts::AttributeHandle<int64_t>(leaf->constAttributeArray(*id)).get(*i));
        } else {
          out.ids.push_back(vpts::AttributeHandle<int32_t>(leaf->constAttributeArray(*id)).get(*i));
        }
      }
      if (mass) out.masses.push_back(vpts::AttributeHandle<float>(leaf->constAttributeArray(*mass)).get(*i));
      if (out.diffuse) {
        out.lifetimes.push_back(vpts::AttributeHandle<float>(leaf->constAttributeArray(*lifetime)).get(*i));
        out.types.push_back(vpts::AttributeHandle<int32_t>(leaf->constAttributeArray(*type)).get(*i));
        if (age) out.ages.push_back(vpts::AttributeHandle<float>(leaf->constAttributeArray(*age)).get(*i));
      }
    }
  }
  return out;
}

std::string grid_type_summary(const vdb::GridBase& g) { return g.type(); }


// A grid of values read in full: its class, count and, for a float grid, range and integral.
VdbVolumeInfo volume_info(const vdb::GridBase& grid) {
  VdbVolumeInfo v;
  v.name = grid.getName();
  v.grid_class = vdb::GridBase::gridClassToString(grid.getGridClass());
  const double voxel = grid.transform().voxelSize().x();
  v.active_voxels = grid.activeVoxelCount();
  if (const auto* floats = dynamic_cast<const vdb::FloatGrid*>(&grid)) {
    v.scalar = true;
    bool first = true;
    double sum = 0.0;
    for (auto it = floats->cbeginValueOn(); it; ++it) {
      const double value = *it;
      v.min = first ? value : std::min(v.min, value), v.max = first ? value : std::max(v.max, value), first = false;
      sum += value * double(it.getVoxelCount());
    }
    v.integral = sum * voxel * voxel * voxel;
  }
  return v;
}

[[noreturn]] void fail_without_points(const std::string& where, const VdbPointsInfo& meta) {
  std::string names;
  for (const VdbGridInfo& g : meta.grids) names += str(names.empty() ? "" : ", ", "'", g.name, "' (", g.type, ")");
  fail(where, ": holds no point data grid (its grids: ", names.empty() ? "none" : names,
       "); spume reads particles, e.g. Mantaflow's 'particles' grid or Houdini's VDB points",
       names.empty() ? "" : "; 'spume info' describes volumes");
}

// Every point grid read (or the one named), merged in the file's order, with the checks every reader
// needs. A file without points fails, unless `volumes` is given: then its grids are read into it.
GridRead read_vdb(const std::filesystem::path& path, const std::string& grid_name, VdbPointsInfo& meta,
                  int& frame_index, double& frame_time, std::vector<VdbVolumeInfo>* volumes) {
  initialize_openvdb();
  const std::string where = path.string();
  if (!has_vdb_magic(path)) fail(where, ": not an OpenVDB file (no VDB magic number at its start)");
  meta = VdbPointsInfo{};
  GridRead all;
  int point_grids = 0, used_grids = 0, grids_with_velocity = 0, grids_with_ids = 0, grids_with_mass = 0;
  int diffuse_grids = 0;
  // A damaged file can make OpenVDB abort or allocate without bound: where the process asked for it,
  // a child reads the file first (sim/io/contained_read.h).
  check_read_in_child(path, "vdb", grid_name);
  std::error_code size_error;
  const uint64_t file_bytes = std::filesystem::file_size(path, size_error);
  try {
    vdb::io::File file(where);
    file.open(/*delayLoad=*/false);
    const vdb::GridPtrVecPtr headers = file.readAllGridMetadata();
    for (const vdb::GridBase::Ptr& header : *headers) {
      VdbGridInfo g;
      g.name = header->getName();
      g.type = grid_type_summary(*header);
      g.voxel_size = header->transform().voxelSize().x();
      g.points = header->isType<vpts::PointDataGrid>();
      if (!g.points) {
        if (const auto count = header->getMetadata<vdb::Int64Metadata>(vdb::GridBase::META_FILE_VOXEL_COUNT))
          g.count = uint64_t(std::max<int64_t>(count->value(), 0));
        meta.grids.push_back(g);
        continue;
      }
      ++point_grids;
      const auto grid = vdb::gridPtrCast<vpts::PointDataGrid>(file.readGrid(g.name));
      if (!grid) fail(where, ": grid '", g.name, "' could not be read as points");
      g.count = vpts::pointCount(grid->tree());
      if (const auto leaf = grid->tree().cbeginLeaf()) {
        const auto& d = leaf->attributeSet().descriptor();
        for (const auto& [name, index] : d.map()) {
          const auto [type, codec] = attribute_type(d, index);
          meta.attributes.push_back({g.name, name, type, codec});
        }
      }
      g.used = grid_name.empty() || grid_name == g.name;
      if (g.used) {
        GridRead read = read_point_grid(*grid, where);
        ++used_grids;
        grids_with_velocity += !read.velocity_name.empty();
        grids_with_ids += !read.id_name.empty();
        grids_with_mass += !read.mass_name.empty();
        diffuse_grids += read.diffuse;
        if (!read.velocity_name.empty()) meta.velocity_attribute = read.velocity_name;
        if (!read.id_name.empty()) meta.id_attribute = read.id_name;
        if (!read.mass_name.empty()) meta.mass_attribute = read.mass_name;
        if (const auto f = grid->getMetadata<vdb::Int32Metadata>("frame")) frame_index = f->value();
        if (const auto t = grid->getMetadata<vdb::DoubleMetadata>("time")) frame_time = t->value();
        auto append = [](auto& to, const auto& from) { to.insert(to.end(), from.begin(), from.end()); };
        append(all.positions, read.positions);
        append(all.velocities, read.velocities);
        append(all.ids, read.ids);
        append(all.masses, read.masses);
        append(all.lifetimes, read.lifetimes);
        append(all.ages, read.ages);
        append(all.types, read.types);
      }
      meta.grids.push_back(g);
    }
    if (point_grids == 0 && volumes && !meta.grids.empty()) {
      for (const VdbGridInfo& g : meta.grids) {
        const vdb::GridBase::Ptr grid = file.readGrid(g.name);
        volumes->push_back(volume_info(*grid));
        if (const auto f = grid->getMetadata<vdb::Int32Metadata>("frame")) frame_index = f->value();
        if (const auto t = grid->getMetadata<vdb::DoubleMetadata>("time")) frame_time = t->value();
      }
      file.close();
      return GridRead{};
    }
    file.close();
  } catch (const Error&) {
    throw;
  } catch (const std::bad_alloc&) {
    if (const uint64_t budget = read_budget_in_force())
      fail(where, ": cannot read this OpenVDB file: reading it asked for more than ", budget >> 20,
            " MiB (256 MiB + 64 x its ", file_bytes, " bytes), which a sound file never needs: a length inside it is "
           "damaged");
    fail(where, ": ", out_of_memory_message(str("reading this OpenVDB file of ", byte_size_text(file_bytes))));
  } catch (const std::exception& e) {
    fail(where, ": cannot read this OpenVDB file (cut short or damaged?): ", e.what());
  }
  if (point_grids == 0) fail_without_points(where, meta);
  if (!grid_name.empty() && used_grids == 0) {
    std::string names;
    for (const VdbGridInfo& g : meta.grids)
      if (g.points) names += str(names.empty() ? "" : ", ", "'", g.name, "'");
    fail(where, ": no point data grid named '", grid_name, "' (fluid.vdb_grid); its point grids: ", names);
  }
  if (grids_with_velocity != 0 && grids_with_velocity != used_grids)
    fail(where, ": some point grids have velocities and some do not; name one with fluid.vdb_grid");
  if (grids_with_ids != 0 && grids_with_ids != used_grids)
    fail(where, ": some point grids have ids and some do not; name one with fluid.vdb_grid");
  if (grids_with_mass != 0 && grids_with_mass != used_grids)
    fail(where, ": some point grids have masses and some do not; name one with fluid.vdb_grid");
  all.diffuse = diffuse_grids > 0 && diffuse_grids == used_grids && grids_with_ids == used_grids &&
                grids_with_velocity == used_grids;
  std::string used;
  for (const VdbGridInfo& g : meta.grids)
    if (g.used) used += str(used.empty() ? "" : ", ", "'", g.name, "'");
  meta.choice = grid_name.empty()
                    ? str(used_grids == 1 ? "the point grid " : "every point grid: ", used,
                          used_grids == 1 ? " (the only one)" : " (fluid.vdb_grid names one)")
                    : str("the point grid ", used, " (fluid.vdb_grid)");
  return all;
}

// spume's diffuse export as the diffuse frame it was written from (positions and velocities within the
// writer's quantisation).
DiffuseFrame diffuse_frame(GridRead& read, const std::string& where) {
  DiffuseFrame frame;
  frame.positions = std::move(read.positions);
  frame.velocities = std::move(read.velocities);
  frame.lifetimes = std::move(read.lifetimes);
  frame.ids.reserve(read.ids.size());
  frame.types.reserve(read.types.size());
  // The writer stores each unsigned 64-bit id's bits as an int64 (OpenVDB has no uint64 attribute): ids
  // whose parent is 2^31 or more read as negative, and come back whole as unsigned.
  for (const int64_t id : read.ids) frame.ids.push_back(uint64_t(id));
  for (size_t i = 0; i < read.types.size(); ++i) {
    if (read.types[i] < 0 || read.types[i] >= kDiffuseTypeCount)
      fail(where, ": diffuse particle ", i, " has type ", read.types[i], "; allowed 0 spray, 1 foam, 2 bubble");
    frame.types.push_back(DiffuseType(read.types[i]));
  }
  frame.validate(where);
  return frame;
}

}  // namespace

VdbContents read_contents(const std::filesystem::path& path, const std::string& grid_name, VdbPointsInfo* info) {
  const std::string where = path.string();
  VdbPointsInfo local;
  VdbContents contents;
  GridRead read = read_vdb(path, grid_name, info ? *info : local, contents.frame_index, contents.time,
                           &contents.volumes);
  if (!contents.volumes.empty()) return contents;
  if (read.diffuse) {
    contents.diffuse = diffuse_frame(read, where);
    if (read.ages.size() == contents.diffuse->size()) contents.diffuse_ages = std::move(read.ages);
    contents.diffuse->index = contents.frame_index;
    contents.diffuse->time = contents.time;
    return contents;
  }
  FluidFrame& frame = contents.fluid;
  frame.positions = std::move(read.positions);
  frame.velocities = std::move(read.velocities);
  frame.masses = std::move(read.masses);
  for (int64_t id : read.ids) {
    if (id < 0 || id > int64_t(UINT32_MAX))
      fail(where, ": id ", id, " is outside 0 .. ", UINT32_MAX, " (spume's fluid particle ids are unsigned 32-bit)");
    frame.ids.push_back(uint32_t(id));
  }
  frame.validate(where);
  return contents;
}

FluidFrame read_points(const std::filesystem::path& path, const std::string& grid_name, VdbPointsInfo* info) {
  VdbPointsInfo local;
  VdbContents contents = read_contents(path, grid_name, info ? info : &local);
  if (!contents.volumes.empty()) fail_without_points(path.string(), info ? *info : local);
  if (contents.diffuse)
    fail(path.string(), ": holds spume's diffuse particles (spray, foam and bubbles with their lifetimes, types "
         "and 64-bit ids: output.vdb), not a fluid frame; 'spume info' describes it");
  return std::move(contents.fluid);
}

}  // namespace spume::openvdb_io
