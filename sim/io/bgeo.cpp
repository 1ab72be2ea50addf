#include "sim/io/bgeo.h"

#include <bit>
#include <climits>
#include <initializer_list>
#include <ostream>

#include "sim/core/atomic_file.h"
#include "sim/core/error.h"
#include "sim/io/attribute_names.h"
#include "sim/io/io_bytes.h"

namespace spume {
namespace {

using io::Endian;

constexpr int kFloat = 0, kInt = 1, kIndex = 4, kVector = 5;

const char* type_name(int type) {
  switch (type) {
    case kFloat: return "float";
    case kInt: return "int";
    case kIndex: return "index";
    case kVector: return "vector";
  }
  return "unknown";
}

struct Attr {
  std::string name;
  int type = 0;
  int size = 0;
  size_t word = 0;  // offset in 32-bit words within a point record (the position takes words 0..3)
};

// The decompressed file plus where each point attribute lives in it.
struct Parsed {
  std::string where;
  std::string bytes;
  BgeoInfo info;
  std::vector<Attr> attrs;
  size_t stride = 4;  // words per point
  size_t points_offset = 0;

  const Attr* find(std::string_view name) const {
    for (const Attr& a : attrs)
      if (a.name == name) return &a;
    return nullptr;
  }
  template <typename T>
  T word(size_t point, size_t w) const {
    return io::load<T>(bytes.data() + points_offset + (point * stride + w) * 4, Endian::Big);
  }
};

// Big-endian values read in order from the front of a file (io::PrefixReader), which reads or inflates
// only as far as they reach: the magic is checked on the first bytes, and a header's claim that
// exceeds what the file can hold fails before anything is inflated.
class HeaderCursor {
 public:
  explicit HeaderCursor(io::PrefixReader& file) : file_(file) {}
  size_t offset() const { return pos_; }
  const std::string& where() const { return file_.where(); }
  bool at_end() { return file_.first(pos_ + 1).size() == pos_; }

  // A view of the next n bytes, valid until the next read.
  std::string_view take(size_t n, std::string_view what) {
    if (n > room())
      fail(where(), ": truncated or corrupt: ", what, " needs ", n, " bytes at offset ", pos_,
           ", more than the file can hold");
    const std::string_view have = file_.first(pos_ + n);
    if (have.size() < pos_ + n)
      fail(where(), ": truncated: ", what, " needs ", n, " bytes at offset ", pos_, " but only ", have.size() - pos_,
           " remain");
    pos_ += n;
    return have.substr(pos_ - n);
  }
  void skip(size_t n, std::string_view what) { take(n, what); }
  // Fails without reading when count elements of elem_size bytes cannot be in the file.
  void require_array(uint64_t count, size_t elem_size, std::string_view what) const {
    if (elem_size != 0 && count > room() / elem_size)
      fail(where(), ": truncated or corrupt: ", what, " claims ", count, " elements of ", elem_size,
           " bytes at offset ", pos_, ", more than the file can hold (", file_.gzipped() ? "at most " : "",
           room(), " bytes remain", file_.gzipped() ? " once decompressed)" : ")");
  }
  uint8_t peek(std::string_view what) {
    const std::string_view have = file_.first(pos_ + 1);
    if (have.size() < pos_ + 1) fail(where(), ": truncated: ", what, " at offset ", pos_, " is past the end");
    return uint8_t(have[pos_]);
  }
  template <typename T>
  T read(std::string_view what) {
    return io::load<T>(take(sizeof(T), what).data(), Endian::Big);
  }

 private:
  // At most this many bytes can follow the cursor.
  uint64_t room() const { return file_.size_bound() - std::min<uint64_t>(pos_, file_.size_bound()); }

  io::PrefixReader& file_;
  size_t pos_ = 0;
};

void reject_other_formats(std::string_view b, const std::string& where) {
  const std::string hint = "; spume reads Houdini's binary geometry (.bgeo, .bgeo.gz, .bgeo.sc) and classic BGEO";
  if (b.size() >= 4 && b.substr(0, 4) == "\x7fNSJ")
    fail(where, ": this is Houdini's binary JSON geometry (starts 7F 'NSJ'), not classic BGEO; read it as Houdini "
         "geometry (spume does so for any .bgeo that starts this way)");
  const size_t first = b.find_first_not_of(" \t\r\n");
  if (first != std::string_view::npos && (b[first] == '{' || b[first] == '['))
    fail(where, ": this is Houdini's ASCII JSON geometry, not classic BGEO; save it from Houdini as .bgeo or .bgeo.sc",
         hint);
  if (b.substr(0, 9) == "PGEOMETRY")
    fail(where, ": this is classic ASCII .geo, not binary BGEO", hint);
  if (b.size() < 5 || b.substr(0, 5) != "BgeoV") {
    std::string found;
    for (size_t i = 0; i < std::min<size_t>(b.size(), 5); ++i) found += str(i ? " " : "", std::hex, int(uint8_t(b[i])));
    fail(where, ": not a BGEO file: first bytes are ", found.empty() ? std::string("(empty file)") : found,
         "; expected 'BgeoV' (42 67 65 6f 56), optionally gzip-compressed");
  }
}

// Reads `count` attribute definitions; word offsets continue from `stride`, which grows.
std::vector<Attr> read_attribute_table(HeaderCursor& r, int count, const char* kind, size_t& stride) {
  std::vector<Attr> attrs;
  for (int i = 0; i < count; ++i) {
    Attr a;
    const uint16_t name_len = r.read<uint16_t>("attribute name length");
    if (name_len == 0) fail(r.where(), ": ", kind, " attribute ", i, " has an empty name");
    a.name = std::string(r.take(name_len, "attribute name"));
    a.size = r.read<uint16_t>("attribute size");
    a.type = r.read<int32_t>("attribute type");
    if (a.size == 0) fail(r.where(), ": ", kind, " attribute '", a.name, "' has size 0; allowed 1..65535 words");
    if (a.type == kFloat || a.type == kInt || a.type == kVector) {
      r.require_array(uint64_t(a.size), 4, "attribute defaults");
      r.skip(size_t(a.size) * 4, "attribute defaults");
    } else if (a.type == kIndex) {
      const int32_t strings = r.read<int32_t>("indexed string count");
      if (strings < 0) fail(r.where(), ": ", kind, " attribute '", a.name, "' has ", strings, " strings; must be >= 0");
      for (int32_t s = 0; s < strings; ++s) r.skip(r.read<uint16_t>("string length"), "indexed string");
    } else {
      fail(r.where(), ": ", kind, " attribute '", a.name, "' has type ", a.type,
           "; allowed 0 float, 1 int, 4 indexed string, 5 vector");
    }
    a.word = stride;
    stride += size_t(a.size);
    attrs.push_back(std::move(a));
  }
  return attrs;
}

std::vector<PointAttribute> listing(const std::vector<Attr>& attrs) {
  std::vector<PointAttribute> out;
  for (const Attr& a : attrs) out.push_back({a.name, type_name(a.type), a.size});
  return out;
}

// One group record (bgeo.h), checked to have one bit an element; returns its name and member count.
std::pair<std::string, size_t> read_group(HeaderCursor& r, size_t elements, const char* what) {
  const bool ordered = r.peek(what) == 0x01;
  if (ordered) r.skip(1, "ordered group flag");
  const uint16_t length = r.read<uint16_t>("group name length");
  std::string name(r.take(length, "group name"));
  const int32_t bits = r.read<int32_t>("group bit count");
  if (bits < 0 || size_t(bits) != elements)
    fail(r.where(), ": ", what, " '", name, "' has ", bits, " bits for ", elements, " elements (file corrupt)");
  const size_t words = (size_t(bits) + 31) / 32;
  r.require_array(words, 4, "group bit mask");
  size_t members = 0;
  for (size_t k = 0; k < words; ++k) members += size_t(std::popcount(r.read<uint32_t>("group bit mask")));
  if (ordered) {
    const int32_t n = r.read<int32_t>("ordered group count");
    if (n < 0) fail(r.where(), ": ", what, " '", name, "' orders ", n, " elements (file corrupt)");
    for (int32_t k = 0; k < n; ++k)
      if (r.read<int32_t>("ordered group index") < 0) r.skip(4, "ordered group profile");
  }
  return {std::move(name), members};
}

// The header first, the rest only as far as it says: no byte past what the header accounts for is
// read or inflated but one, to tell a clean end from trailing data.
Parsed parse(const std::filesystem::path& path) {
  Parsed p;
  p.where = path.string();
  io::PrefixReader file(path);
  p.info.gzipped = file.gzipped();
  // Enough to recognise the other formats (the JSON and ASCII geometries start with text).
  reject_other_formats(file.first(size_t(1) << 12), p.where);

  HeaderCursor r(file);
  r.skip(5, "magic");
  p.info.version = r.read<int32_t>("version");
  if (p.info.version != 5) fail(p.where, ": BGEO version ", p.info.version, "; only version 5 (classic) is supported");
  const char* names[] = {"point count",           "primitive count",  "point group count",
                         "primitive group count", "point attributes", "vertex attributes",
                         "primitive attributes",  "detail attributes"};
  int32_t counts[8];
  for (int i = 0; i < 8; ++i) {
    counts[i] = r.read<int32_t>(names[i]);
    if (counts[i] < 0) fail(p.where, ": ", names[i], " is ", counts[i], "; must be >= 0");
  }
  p.info.point_count = size_t(counts[0]);
  p.info.primitive_count = counts[1];
  p.info.point_group_count = counts[2];
  p.info.primitive_group_count = counts[3];

  p.attrs = read_attribute_table(r, counts[4], "point", p.stride);
  p.info.point_attributes = listing(p.attrs);

  r.require_array(p.info.point_count, p.stride * 4, "point data");
  p.points_offset = r.offset();
  r.skip(p.info.point_count * p.stride * 4, "point data");
  const auto keep_points = [&] {
    p.bytes = file.release();
    for (size_t i = 0; i < p.info.point_count; ++i)
      p.info.bounds.extend(Vec3f(p.word<float>(i, 0), p.word<float>(i, 1), p.word<float>(i, 2)));
  };

  // Primitives (Houdini particle systems) would need their own parsers; the points are all spume
  // needs, so the rest is left unread rather than half-understood.
  if (counts[1] != 0 || counts[5] != 0 || counts[6] != 0) {
    p.info.trailing_data_skipped = true;
    keep_points();
    return p;
  }
  size_t detail_stride = 0;
  p.info.detail_attributes = listing(read_attribute_table(r, counts[7], "detail", detail_stride));
  r.skip(detail_stride * 4, "detail attribute values");
  for (int32_t g = 0; g < counts[2]; ++g) p.info.point_groups.push_back(read_group(r, p.info.point_count, "point group"));
  for (int32_t g = 0; g < counts[3]; ++g) read_group(r, 0, "primitive group");
  const std::string_view end = r.take(2, "end marker 00 FF");
  if (uint8_t(end[0]) != 0x00 || uint8_t(end[1]) != 0xff)
    fail(p.where, ": missing end marker: found bytes ", int(uint8_t(end[0])), " ", int(uint8_t(end[1])),
         " at offset ", r.offset() - 2, "; expected 00 FF (file corrupt or not classic BGEO)");
  if (!r.at_end()) fail(p.where, ": unexpected bytes after the end marker at offset ", r.offset(), " (file corrupt)");
  keep_points();
  return p;
}

// The attribute of this name, if any, checked to be `size` words of one of `types`.
const Attr* pick(const Parsed& p, std::string_view name, std::initializer_list<int> types, int size, const char* role) {
  const Attr* a = p.find(name);
  if (!a) return nullptr;
  bool type_ok = false;
  for (int t : types) type_ok |= a->type == t;
  if (!type_ok || a->size != size) {
    std::string allowed;
    for (int t : types) allowed += str(allowed.empty() ? "" : " or ", type_name(t));
    fail(p.where, ": attribute '", a->name, "' is ", type_name(a->type), "[", a->size, "]; ", role, " must be ",
         allowed, "[", size, "]");
  }
  return a;
}

// The first attribute of one of the role's names (io/attribute_names.h), checked as above.
const Attr* pick(const Parsed& p, io::AttributeRole role, std::initializer_list<int> types, int size) {
  for (const std::string_view name : io::attribute_names(role))
    if (const Attr* a = pick(p, name, types, size, io::attribute_role_text(role))) return a;
  return nullptr;
}

Vec3f vec3(const Parsed& p, size_t i, const Attr* a) {
  return Vec3f(p.word<float>(i, a->word), p.word<float>(i, a->word + 1), p.word<float>(i, a->word + 2));
}

// Big-endian record writer; `attrs` are (name, type, size) in record order.
struct Writer {
  std::string out;
  void i32(int32_t v) { io::store(out, v, Endian::Big); }
  void f32(float v) { io::store(out, v, Endian::Big); }
  void vec(const Vec3f& v) {
    f32(v.x());
    f32(v.y());
    f32(v.z());
  }
  void header(size_t points, const std::vector<Attr>& attrs, int point_groups = 0) {
    out += "BgeoV";
    i32(5);
    const int32_t counts[8] = {int32_t(points), 0, point_groups, 0, int32_t(attrs.size()), 0, 0, 0};
    for (int32_t c : counts) i32(c);
    for (const Attr& a : attrs) {
      io::store(out, uint16_t(a.name.size()), Endian::Big);
      out += a.name;
      io::store(out, uint16_t(a.size), Endian::Big);
      i32(a.type);
      for (int k = 0; k < a.size; ++k) i32(0);
    }
  }
  // An unordered point group over `n` points: the members' bits, least significant first in each word.
  template <typename Member>
  void group(const std::string& name, size_t n, Member&& member) {
    io::store(out, uint16_t(name.size()), Endian::Big);
    out += name;
    i32(int32_t(n));
    for (size_t w = 0; w < (n + 31) / 32; ++w) {
      uint32_t word = 0;
      for (size_t b = 0; b < 32 && w * 32 + b < n; ++b) word |= uint32_t(member(w * 32 + b)) << b;
      io::store(out, word, Endian::Big);
    }
  }
  void finish_and_write(const std::filesystem::path& path) {
    out += std::string("\x00\xff", 2);  // (no detail attributes, any groups written,) the end marker
    const std::string compressed = io::gzip_compress(out);
    write_file_atomically(path, [&](std::ostream& s) { s.write(compressed.data(), std::streamsize(compressed.size())); });
  }
};

void check_point_count(const std::filesystem::path& path, size_t n) {
  if (n > size_t(INT32_MAX)) fail(path.string(), ": ", n, " points; BGEO holds at most ", INT32_MAX);
}

}  // namespace

FluidFrame read_bgeo(const std::filesystem::path& path, BgeoInfo* info) {
  const Parsed p = parse(path);
  const size_t n = p.info.point_count;
  FluidFrame frame;
  frame.positions.resize(n);
  for (size_t i = 0; i < n; ++i) frame.positions[i] = Vec3f(p.word<float>(i, 0), p.word<float>(i, 1), p.word<float>(i, 2));
  if (const Attr* v = pick(p, io::AttributeRole::Velocity, {kVector, kFloat}, 3)) {
    frame.velocities.resize(n);
    for (size_t i = 0; i < n; ++i) frame.velocities[i] = vec3(p, i, v);
  }
  if (const Attr* id = pick(p, io::AttributeRole::Id, {kInt}, 1)) {
    frame.ids.resize(n);
    for (size_t i = 0; i < n; ++i) {
      const int32_t value = p.word<int32_t>(i, id->word);
      if (value < 0) fail(p.where, ": particle ", i, " has id ", value, "; ids must be >= 0");
      frame.ids[i] = uint32_t(value);
    }
  }
  if (const Attr* m = pick(p, io::AttributeRole::Mass, {kFloat}, 1)) {
    frame.masses.resize(n);
    for (size_t i = 0; i < n; ++i) frame.masses[i] = p.word<float>(i, m->word);
  }
  frame.validate(p.where);
  if (info) *info = p.info;
  return frame;
}

BgeoInfo read_bgeo_info(const std::filesystem::path& path) { return parse(path).info; }

DiffuseFrame read_bgeo_diffuse(const std::filesystem::path& path) {
  const Parsed p = parse(path);
  const Attr* v = pick(p, "v", {kVector, kFloat}, 3, "a velocity");
  const Attr* type = pick(p, "type", {kInt}, 1, "the diffuse type");
  const Attr* life = pick(p, "lifetime", {kFloat}, 1, "the lifetime");
  if (!v || !type || !life)
    fail(p.where, ": not a spume diffuse BGEO: needs point attributes 'v' (vector[3]), 'type' (int) and 'lifetime' (float)");
  const Attr* parent = pick(p, "id", {kInt}, 1, "the parent id");
  const Attr* birth = pick(p, "birth", {kInt}, 1, "the birth step");
  const Attr* sample = pick(p, "sample", {kInt}, 1, "the sample index");
  const size_t n = p.info.point_count;
  DiffuseFrame frame;
  frame.resize(n);
  for (size_t i = 0; i < n; ++i) {
    frame.positions[i] = Vec3f(p.word<float>(i, 0), p.word<float>(i, 1), p.word<float>(i, 2));
    frame.velocities[i] = vec3(p, i, v);
    frame.lifetimes[i] = p.word<float>(i, life->word);
    const int32_t t = p.word<int32_t>(i, type->word);
    if (t < 0 || t >= kDiffuseTypeCount)
      fail(p.where, ": diffuse particle ", i, " has type ", t, "; allowed 0 spray, 1 foam, 2 bubble");
    frame.types[i] = DiffuseType(t);
    const uint32_t b = birth ? p.word<uint32_t>(i, birth->word) : 0;
    const uint32_t s = sample ? p.word<uint32_t>(i, sample->word) : 0;
    if (b > kMaxBirthStep || s > kMaxSamplesPerStep)
      fail(p.where, ": diffuse particle ", i, " has birth ", b, " and sample ", s, "; allowed birth <= ", kMaxBirthStep,
           ", sample <= ", kMaxSamplesPerStep);
    frame.ids[i] = diffuse_id(parent ? p.word<uint32_t>(i, parent->word) : 0, b, s);
  }
  frame.validate(p.where);
  return frame;
}

void write_bgeo(const std::filesystem::path& path, const FluidFrame& frame) {
  frame.validate(path.string());
  const size_t n = frame.size();
  check_point_count(path, n);
  std::vector<Attr> attrs;
  if (frame.has_ids()) attrs.push_back({"id", kInt, 1, 0});
  if (frame.has_velocities()) attrs.push_back({"v", kVector, 3, 0});
  if (!frame.masses.empty()) attrs.push_back({"mass", kFloat, 1, 0});
  Writer w;
  w.out.reserve(256 + n * (4 + attrs.size() * 3) * 4);
  w.header(n, attrs);
  for (size_t i = 0; i < n; ++i) {
    const Vec3f& x = frame.positions[i];
    w.vec(x);
    w.f32(1.0f);
    if (frame.has_ids()) {
      if (frame.ids[i] > uint32_t(INT32_MAX))
        fail(path.string(), ": particle ", i, " has id ", frame.ids[i], "; BGEO ids are int32, at most ", INT32_MAX);
      w.i32(int32_t(frame.ids[i]));
    }
    if (frame.has_velocities()) w.vec(frame.velocities[i]);
    if (!frame.masses.empty()) w.f32(frame.masses[i]);
  }
  w.finish_and_write(path);
}

void write_bgeo(const std::filesystem::path& path, const DiffuseFrame& frame, std::span<const float> ages) {
  frame.validate(path.string());
  const size_t n = frame.size();
  check_point_count(path, n);
  if (!ages.empty() && ages.size() != n) fail(path.string(), ": ", ages.size(), " ages for ", n, " particles");
  std::vector<Attr> attrs = {
      {"v", kVector, 3, 0}, {"type", kInt, 1, 0}, {"lifetime", kFloat, 1, 0},
      {"id", kInt, 1, 0},   {"birth", kInt, 1, 0}, {"sample", kInt, 1, 0}};
  if (!ages.empty()) attrs.insert(attrs.end(), {{"age", kFloat, 1, 0}, {"life", kFloat, 1, 0}});
  Writer w;
  w.out.reserve(256 + n * 11 * 4 + n * 3 / 8);
  w.header(n, attrs, kDiffuseTypeCount);
  for (size_t i = 0; i < n; ++i) {
    const Vec3f& x = frame.positions[i];
    const Vec3f& v = frame.velocities[i];
    w.vec(x);
    w.f32(1.0f);
    w.vec(v);
    w.i32(int32_t(frame.types[i]));
    w.f32(frame.lifetimes[i]);
    w.i32(int32_t(diffuse_id_parent(frame.ids[i])));
    w.i32(int32_t(diffuse_id_step(frame.ids[i])));
    w.i32(int32_t(diffuse_id_sample(frame.ids[i])));
    if (!ages.empty()) {
      w.f32(ages[i]);
      w.f32(ages[i] + frame.lifetimes[i]);
    }
  }
  // Houdini selects by group (`@group_spray`, a Blast by name): one per type.
  for (int t = 0; t < kDiffuseTypeCount; ++t)
    w.group(to_string(DiffuseType(t)), n, [&](size_t i) { return frame.types[i] == DiffuseType(t); });
  w.finish_and_write(path);
}

}  // namespace spume
