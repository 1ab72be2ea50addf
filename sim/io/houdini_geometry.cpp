#include "sim/io/houdini_geometry.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <cstdint>
#include <limits>
#include <map>

#include "sim/core/error.h"
#include "sim/io/attribute_names.h"
#include "sim/io/houdini_json.h"
#include "sim/io/houdini_scf.h"
#include "sim/io/houdini_values.h"
#include "sim/io/io_bytes.h"

namespace spume {
namespace {

using hjson::Kind;
using hjson::Reader;

constexpr int64_t kMaxPoints = std::numeric_limits<int32_t>::max();

struct Bytes {
  std::string json;
  std::string container = "none";
  size_t chunks = 0;
};

// Houdini's binary JSON starts with 0x7f and "NSJb" (or "bJSN", byte-swapped).
bool has_binary_json_magic(std::string_view h) {
  return h.size() >= 5 && uint8_t(h[0]) == 0x7f && (h.substr(1, 4) == "NSJb" || h.substr(1, 4) == "bJSN");
}

// The binary JSON of a file, whatever holds it.
Bytes json_bytes(const std::filesystem::path& path) {
  const std::string where = path.string();
  // A .bgeo.sc that is not one is refused on its first bytes, before the file is read.
  const std::string head = io::read_file_head(path, 5);
  if (!has_scf_magic(head) && !io::has_gzip_magic(head) && !has_binary_json_magic(head) &&
      io::lower_file_name(path).ends_with(".bgeo.sc"))
    decompress_scf(head, where);  // says what a .bgeo.sc should start with
  // A .bgeo.sc keeps its index at the end: a cut or damaged one is refused before the whole is read.
  if (has_scf_magic(head)) check_scf_ends(head, io::read_file_tail(path, 12), std::filesystem::file_size(path), where);
  std::string file = io::read_file_bytes(path);
  Bytes b;
  if (has_scf_magic(file)) {
    ScfStats stats;
    b.json = decompress_scf(file, where, &stats);
    b.container = "Blosc (.bgeo.sc)";
    b.chunks = stats.chunks;
  } else if (io::has_gzip_magic(file)) {
    b.json = io::gunzip(file, where);
    b.container = "gzip";
  } else {
    b.json = std::move(file);
  }
  return b;
}

// The point attributes spume uses (P and io/attribute_names.h), decoded as the walk meets them: string ids
// defined later in the file may reuse an id, so the walk never goes back.
bool used_attribute(std::string_view name) { return name == "P" || io::attribute_role(name).has_value(); }

struct Wanted {
  int size = 0;
  std::vector<double> values;  // point_count * size
};

struct Walk {
  HoudiniGeometryInfo info;
  std::optional<int64_t> point_count;
  std::map<std::string, Wanted, std::less<>> used;
};

// [key, value, key, value...] or {key: value...}: calls on(key) with the reader at the value, which
// on() must take whole.
template <typename OnKey>
void for_each_key(Reader& r, std::string_view what, OnKey&& on) {
  const hjson::Token open = r.next();
  if (open.kind != Kind::ArrayBegin && open.kind != Kind::MapBegin)
    r.fail_at(open.offset, what, " must be an array of keys and values");
  const Kind close = open.kind == Kind::ArrayBegin ? Kind::ArrayEnd : Kind::MapEnd;
  while (!r.end_of(close)) on(r.string(str(what, " key")));
}

void read_info(Reader& r, HoudiniGeometryInfo& info) {
  for_each_key(r, "info", [&](std::string_view key) {
    if (key == "bounds") {
      const size_t at = r.offset();
      const std::vector<double> b = hjson::read_number_list(r, "info bounds");
      if (b.size() != 6) r.fail_at(at, "info bounds has ", b.size(), " numbers; expected 6");
      Aabb box;
      box.extend(Vec3f(float(b[0]), float(b[2]), float(b[4])));
      box.extend(Vec3f(float(b[1]), float(b[3]), float(b[5])));
      info.info_bounds = box;
    } else if (key == "attribute_ranges") {
      info.info_attribute_ranges = std::string(r.string("info attribute_ranges"));
    } else if (key == "primcount_summary") {
      std::string s(r.string("info primcount_summary"));
      // "   12,854 Polygons\n   23 Packed Geometries\n" -> "12,854 Polygons, 23 Packed Geometries"
      std::string out;
      size_t start = 0;
      while (start < s.size()) {
        size_t end = s.find('\n', start);
        if (end == std::string::npos) end = s.size();
        const std::string line = s.substr(start, end - start);
        const size_t first = line.find_first_not_of(' ');
        if (first != std::string::npos) out += (out.empty() ? "" : ", ") + line.substr(first);
        start = end + 1;
      }
      info.primitive_summary = out;
    } else {
      r.skip_value();
    }
  });
}

// One entry of "pointattributes": [definition, body].
void read_point_attribute(Reader& r, Walk& walk) {
  r.expect(Kind::ArrayBegin, "a point attribute");
  std::string name, type;
  for_each_key(r, "point attribute definition", [&](std::string_view key) {
    if (key == "name") name = r.string("attribute name");
    else if (key == "type") type = r.string("attribute type");
    else r.skip_value();
  });
  if (name.empty()) r.fail_at(r.offset(), "a point attribute without a name");
  int size = 1;
  std::string storage;
  for_each_key(r, str("point attribute '", name, "'"), [&](std::string_view key) {
    if (key == "size") size = int(r.integer(str("size of attribute '", name, "'"), 1, 1 << 16));
    else if (key == "storage") storage = r.string(str("storage of attribute '", name, "'"));
    else if (key == "values" && type == "numeric" &&
             used_attribute(name)) {
      if (!walk.point_count) r.fail_at(r.offset(), "point attributes before the pointcount (file corrupt?)");
      Wanted w{size, {}};
      hjson::read_values(r, uint64_t(*walk.point_count), size, w.values, str("point attribute '", name, "'"));
      walk.used[name] = std::move(w);
    } else {
      r.skip_value();
    }
  });
  if (!r.end_of(Kind::ArrayEnd)) r.fail_at(r.offset(), "point attribute '", name, "' has more than a definition and a body");
  walk.info.point_attributes.push_back({name, type == "numeric" && !storage.empty() ? storage : type, size});
}

void read_attributes(Reader& r, Walk& walk) {
  for_each_key(r, "attributes", [&](std::string_view key) {
    if (key != "pointattributes") return r.skip_value();
    r.expect(Kind::ArrayBegin, "pointattributes");
    while (!r.end_of(Kind::ArrayEnd)) read_point_attribute(r, walk);
  });
}

const Wanted* find_sized(const std::map<std::string, Wanted, std::less<>>& wanted, std::string_view name, int size,
                         const std::string& where, std::string_view role) {
  const auto it = wanted.find(name);
  if (it == wanted.end()) return nullptr;
  if (it->second.size != size)
    fail(where, ": point attribute '", name, "' has ", it->second.size, " components; ", role, " needs ", size);
  return &it->second;
}

// The first of the role's names (io/attribute_names.h) the file holds, of one component.
const Wanted* find_role(const std::map<std::string, Wanted, std::less<>>& wanted, io::AttributeRole role,
                        const std::string& where) {
  for (const std::string_view name : io::attribute_names(role))
    if (const Wanted* w = find_sized(wanted, name, 1, where, io::attribute_role_text(role))) return w;
  return nullptr;
}

}  // namespace

bool is_houdini_geometry(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  char head[5] = {};
  if (!in.read(head, 5)) return false;
  const std::string_view h(head, 5);
  if (has_scf_magic(h) || has_binary_json_magic(h)) return true;
  if (!io::has_gzip_magic(h)) return false;
  try {
    io::PrefixReader gz(path);
    return has_binary_json_magic(gz.first(5));
  } catch (const Error&) {
    return false;  // a corrupt gzip stream: the classic reader says what is wrong with it
  }
}

FluidFrame read_houdini_geometry(const std::filesystem::path& path, HoudiniGeometryInfo* info_out) {
  const std::string where = path.string();
  Bytes bytes = json_bytes(path);
  Walk walk;
  HoudiniGeometryInfo& info = walk.info;
  info.container = bytes.container;
  info.chunks = bytes.chunks;
  info.json_bytes = bytes.json.size();
  const std::string_view json = bytes.json;
  const size_t first = json.find_first_not_of(" \t\r\n");
  if (first != std::string_view::npos && (json[first] == '[' || json[first] == '{'))
    fail(where, ": this is Houdini's ASCII JSON geometry (.geo); spume reads its binary form: save .bgeo or .bgeo.sc");
  Reader r(json, where);

  for_each_key(r, "the geometry", [&](std::string_view key) {
    if (key == "fileversion") info.file_version = r.string("fileversion");
    else if (key == "pointcount") walk.point_count = r.integer("pointcount", 0, kMaxPoints);
    else if (key == "primitivecount") info.primitive_count = size_t(r.integer("primitivecount", 0, INT64_MAX));
    else if (key == "info") read_info(r, info);
    else if (key == "attributes") read_attributes(r, walk);
    else r.skip_value();
  });
  if (!r.at_end()) r.fail_at(r.offset(), "unexpected data after the geometry (file corrupt?)");
  if (!walk.point_count) fail(where, ": Houdini geometry without a pointcount (file corrupt?)");
  const size_t n = size_t(*walk.point_count);
  const auto& wanted = walk.used;
  info.point_count = n;

  FluidFrame frame;
  const Wanted* p = find_sized(wanted, "P", 3, where, "the position");
  if (!p && n > 0) fail(where, ": ", n, " points but no point attribute 'P' (positions)");
  const Wanted* v = nullptr;
  for (const std::string_view name : io::attribute_names(io::AttributeRole::Velocity))
    if ((v = find_sized(wanted, name, 3, where, "a velocity"))) {
      info.velocity_attribute = name;
      break;
    }
  const Wanted* id = find_role(wanted, io::AttributeRole::Id, where);
  const Wanted* mass = find_role(wanted, io::AttributeRole::Mass, where);

  // Which points are particles: with ids, those with an id >= 0.
  std::vector<uint32_t> ids;
  std::vector<bool> keep(n, true);
  if (id) {
    const std::vector<double>& values = id->values;
    ids.reserve(n);
    for (size_t i = 0; i < n; ++i) {
      const double x = values[i];
      if (x != std::floor(x) || x > double(UINT32_MAX))
        fail(where, ": point ", i, " has id ", x, "; ids must be integers up to ", UINT32_MAX);
      if (x < 0) {
        keep[i] = false;
        ++info.points_without_id;
      } else {
        ids.push_back(uint32_t(x));
      }
    }
    frame.ids = std::move(ids);
  }
  const auto kept = [&](const std::vector<double>& values, auto&& put) {
    for (size_t i = 0; i < n; ++i)
      if (keep[i]) put(i, values);
  };
  if (p) {
    const std::vector<double>& values = p->values;
    frame.positions.reserve(n - info.points_without_id);
    for (size_t i = 0; i < n; ++i) {
      const Vec3f x{float(values[3 * i]), float(values[3 * i + 1]), float(values[3 * i + 2])};
      info.point_bounds.extend(x);
      if (keep[i]) frame.positions.push_back(x);
    }
  }
  if (v) {
    const std::vector<double>& values = v->values;
    frame.velocities.reserve(frame.positions.size());
    for (size_t i = 0; i < n; ++i) {
      const Vec3f u{float(values[3 * i]), float(values[3 * i + 1]), float(values[3 * i + 2])};
      info.velocity_range.extend(u);
      if (keep[i]) frame.velocities.push_back(u);
    }
  }
  if (mass) {
    const std::vector<double>& values = mass->values;
    kept(values, [&](size_t i, const std::vector<double>& m) { frame.masses.push_back(float(m[i])); });
  }
  frame.validate(where);
  if (info_out) *info_out = std::move(info);
  return frame;
}

}  // namespace spume
