#include "sim/io/ply.h"

#include <array>
#include <charconv>
#include <cmath>
#include <ostream>

#include "sim/core/atomic_file.h"
#include "sim/core/error.h"
#include "sim/io/attribute_names.h"
#include "sim/io/io_bytes.h"

namespace spume {
namespace {

using io::ByteReader;
using io::Endian;
using io::NumType;

enum class Format { Ascii, BinaryLittle, BinaryBig };

struct Property {
  std::string name;
  std::string type_name;
  NumType type;
  bool list = false;
  NumType count_type;  // lists only
};

struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> props;
};

struct Header {
  Format format = Format::Ascii;
  std::vector<Element> elements;
  size_t body_offset = 0;
};

NumType parse_type(std::string_view name, const std::string& where) {
  struct Entry {
    const char* a;
    const char* b;
    NumType t;
  };
  static const Entry table[] = {
      {"char", "int8", {NumType::Int, 1}},     {"uchar", "uint8", {NumType::UInt, 1}},
      {"short", "int16", {NumType::Int, 2}},   {"ushort", "uint16", {NumType::UInt, 2}},
      {"int", "int32", {NumType::Int, 4}},     {"uint", "uint32", {NumType::UInt, 4}},
      {"float", "float32", {NumType::Float, 4}}, {"double", "float64", {NumType::Float, 8}}};
  for (const Entry& e : table)
    if (name == e.a || name == e.b) return e.t;
  fail(where, ": unknown PLY property type '", name, "'; allowed char uchar short ushort int uint float double ",
       "(or int8 uint8 int16 uint16 int32 uint32 float32 float64)");
}

std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> out;
  io::TokenReader t(line, "");
  while (!t.at_end()) out.push_back(t.next("header word"));
  return out;
}

Header parse_header(std::string_view data, const std::string& where) {
  if (data.substr(0, 3) != "ply" || data.size() < 4 || (data[3] != '\n' && data[3] != '\r'))
    fail(where, ": not a PLY file: it must start with the line 'ply'");
  Header h;
  bool have_format = false;
  size_t pos = 0;
  while (true) {
    const size_t eol = data.find('\n', pos);
    if (eol == std::string_view::npos) fail(where, ": truncated PLY header: no 'end_header' line");
    const std::string_view line = data.substr(pos, eol - pos);
    pos = eol + 1;
    const auto w = words(line);
    if (w.empty() || w[0] == "ply" || w[0] == "comment" || w[0] == "obj_info") continue;
    if (w[0] == "end_header") break;
    if (w[0] == "format") {
      if (w.size() != 3) fail(where, ": malformed PLY format line '", line, "'");
      if (w[1] == "ascii") h.format = Format::Ascii;
      else if (w[1] == "binary_little_endian") h.format = Format::BinaryLittle;
      else if (w[1] == "binary_big_endian") h.format = Format::BinaryBig;
      else fail(where, ": PLY format '", w[1], "'; allowed ascii, binary_little_endian, binary_big_endian");
      have_format = true;
    } else if (w[0] == "element") {
      uint64_t count = 0;
      if (w.size() != 3 || std::from_chars(w[2].data(), w[2].data() + w[2].size(), count).ptr != w[2].data() + w[2].size())
        fail(where, ": malformed PLY element line '", line, "'; expected 'element <name> <count>'");
      h.elements.push_back({std::string(w[1]), count, {}});
    } else if (w[0] == "property") {
      if (h.elements.empty()) fail(where, ": PLY property line '", line, "' before any element line");
      Property p;
      if (w.size() == 5 && w[1] == "list") {
        p.list = true;
        p.count_type = parse_type(w[2], where);
        if (p.count_type.kind == NumType::Float) fail(where, ": PLY list '", w[4], "' has a non-integer count type");
        p.type = parse_type(w[3], where);
        p.type_name = str("list ", w[2], " ", w[3]);
        p.name = std::string(w[4]);
      } else if (w.size() == 3) {
        p.type = parse_type(w[1], where);
        p.type_name = std::string(w[1]);
        p.name = std::string(w[2]);
      } else {
        fail(where, ": malformed PLY property line '", line, "'");
      }
      h.elements.back().props.push_back(std::move(p));
    } else {
      fail(where, ": unknown PLY header keyword '", w[0], "'");
    }
  }
  if (!have_format) fail(where, ": PLY header has no format line");
  h.body_offset = pos;
  return h;
}

constexpr size_t kHeadBytes = size_t(1) << 16;

// The magic line, and a header of text up to 'end_header' (in the file's first bytes; a longer header
// is checked whole once read): a file that is not PLY is refused on its first bytes, whatever its size.
void check_header_text(std::string_view head, const std::string& where) {
  if (head.substr(0, 3) != "ply" || head.size() < 4 || (head[3] != '\n' && head[3] != '\r'))
    fail(where, ": not a PLY file: it must start with the line 'ply'");
  const std::string_view header = head.substr(0, head.find("end_header"));
  for (size_t i = 0; i < header.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(header[i]);
    if (c < 0x20 && c != '\n' && c != '\r' && c != '\t')
      fail(where, ": not a PLY file: byte ", int(c), " at offset ", i, " in its header, which is text up to 'end_header'");
  }
}

// Values of the body in file order, from text tokens or binary words.
class Body {
 public:
  Body(std::string_view data, const Header& h, const std::string& where)
      : format_(h.format),
        total_(data.size()),
        bin_(data.substr(h.body_offset), where, h.format == Format::BinaryBig ? Endian::Big : Endian::Little),
        text_(data, where, h.body_offset) {}

  double value(NumType t, std::string_view what) {
    if (format_ == Format::Ascii) return text_.number(what);
    return io::load_number(bin_.take(t.size, what).data(), t, bin_.endian());
  }
  // Rejects element counts that cannot fit the remaining bytes, before anything is allocated.
  void check_count(const Element& e, const std::string& where) const {
    size_t min_row = 0;  // bytes (binary) or tokens (ascii) of a row whose lists are empty
    for (const Property& p : e.props) min_row += format_ == Format::Ascii ? 1 : (p.list ? p.count_type.size : p.type.size);
    const size_t room = format_ == Format::Ascii ? total_ - text_.offset() : bin_.remaining();
    if (min_row > 0 && e.count > room / min_row)
      fail(where, ": truncated or corrupt: element '", e.name, "' claims ", e.count, " rows but only ", room,
           " bytes of data remain");
  }
  void skip_element(const Element& e) {
    if (e.props.empty()) return;
    bool fixed = format_ != Format::Ascii;
    size_t row = 0;
    for (const Property& p : e.props) {
      fixed = fixed && !p.list;
      row += p.type.size;
    }
    if (fixed) return bin_.skip(size_t(e.count) * row, e.name);  // count checked by check_count
    for (uint64_t r = 0; r < e.count; ++r)
      for (const Property& p : e.props) skip_property(p, e.name);
  }
  void skip_property(const Property& p, std::string_view what) {
    if (!p.list) return void(value(p.type, what));
    const double n = value(p.count_type, what);
    // Each list entry takes at least one byte, so a longer list is corrupt (and must not drive a loop).
    if (!(n >= 0 && n == std::floor(n) && n <= double(total_)))
      fail(bin_.where(), ": invalid list length ", n, " in element '", what, "'");
    if (format_ != Format::Ascii) {
      bin_.require_array(uint64_t(n), p.type.size, what);
      return bin_.skip(size_t(n) * p.type.size, what);
    }
    for (uint64_t i = 0; i < uint64_t(n); ++i) value(p.type, what);
  }

 private:
  Format format_;
  size_t total_;
  ByteReader bin_;
  io::TokenReader text_;
};

int find(const Element& e, std::string_view name) {
  for (size_t i = 0; i < e.props.size(); ++i)
    if (!e.props[i].list && e.props[i].name == name) return int(i);
  return -1;
}

// The first of the role's names (io/attribute_names.h) the element has.
int find(const Element& e, io::AttributeRole role) {
  for (const std::string_view name : io::attribute_names(role))
    if (const int i = find(e, name); i >= 0) return i;
  return -1;
}

// The velocity's three scalar properties under the first of its names the element has, spelt `vx`
// or `velocity_x` (io::velocity_component); {-1, -1, -1} without one. `spelt`: the x component's name.
std::array<int, 3> find_velocity(const Element& e, std::string& spelt) {
  for (const std::string_view name : io::attribute_names(io::AttributeRole::Velocity))
    for (const bool underscore : {false, true}) {
      std::array<int, 3> v;
      for (int a = 0; a < 3; ++a) v[a] = find(e, io::velocity_component(name, underscore, a));
      if (v[0] >= 0 || v[1] >= 0 || v[2] >= 0) {
        spelt = io::velocity_component(name, underscore, 0);
        return v;
      }
    }
  return {-1, -1, -1};
}

}  // namespace

FluidFrame read_ply(const std::filesystem::path& path, std::vector<PointAttribute>* attributes) {
  const std::string where = path.string();
  check_header_text(io::read_file_head(path, kHeadBytes), where);
  const std::string data = io::read_file_bytes(path);
  const Header h = parse_header(data, where);
  Body body(data, h, where);
  FluidFrame frame;
  bool found_vertex = false;
  for (const Element& e : h.elements) {
    body.check_count(e, where);
    if (e.name != "vertex" || found_vertex) {
      body.skip_element(e);
      continue;
    }
    found_vertex = true;
    const std::array<int, 3> x = {find(e, "x"), find(e, "y"), find(e, "z")};
    std::string velocity_x;
    const std::array<int, 3> v = find_velocity(e, velocity_x);
    const int id = find(e, io::AttributeRole::Id), mass = find(e, io::AttributeRole::Mass);
    if (x[0] < 0 || x[1] < 0 || x[2] < 0) fail(where, ": PLY element 'vertex' lacks scalar properties x, y and z");
    const bool has_v = v[0] >= 0 || v[1] >= 0 || v[2] >= 0;
    if (has_v && (v[0] < 0 || v[1] < 0 || v[2] < 0)) {
      const std::string name = velocity_x.substr(0, velocity_x.size() - 1);
      fail(where, ": PLY vertex velocity is incomplete; need all of ", name, "x ", name, "y ", name, "z");
    }
    const size_t n = size_t(e.count);
    frame.positions.resize(n);
    if (has_v) frame.velocities.resize(n);
    if (id >= 0) frame.ids.resize(n);
    if (mass >= 0) frame.masses.resize(n);
    std::vector<double> row(e.props.size());
    for (size_t i = 0; i < n; ++i) {
      for (size_t k = 0; k < e.props.size(); ++k) {
        if (e.props[k].list) body.skip_property(e.props[k], "vertex");
        else row[k] = body.value(e.props[k].type, e.props[k].name);
      }
      frame.positions[i] = Vec3f(float(row[x[0]]), float(row[x[1]]), float(row[x[2]]));
      if (has_v) frame.velocities[i] = Vec3f(float(row[v[0]]), float(row[v[1]]), float(row[v[2]]));
      if (id >= 0) frame.ids[i] = io::to_particle_id(row[id], i, where);
      if (mass >= 0) frame.masses[i] = float(row[mass]);
    }
    if (attributes) {
      attributes->clear();
      for (const Property& p : e.props) attributes->push_back({p.name, p.type_name, 1});
    }
  }
  if (!found_vertex) fail(where, ": PLY file has no 'vertex' element");
  frame.validate(where);
  return frame;
}

void write_ply(const std::filesystem::path& path, const FluidFrame& frame) {
  frame.validate(path.string());
  const size_t n = frame.size();
  std::string out = str("ply\nformat binary_little_endian 1.0\ncomment spume fluid frame ", frame.index, " time ",
                        frame.time, "\nelement vertex ", n, "\nproperty float x\nproperty float y\nproperty float z\n");
  if (frame.has_velocities()) out += "property float vx\nproperty float vy\nproperty float vz\n";
  if (frame.has_ids()) out += "property uint id\n";
  if (!frame.masses.empty()) out += "property float mass\n";
  out += "end_header\n";
  out.reserve(out.size() + n * 32);
  for (size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) io::store(out, frame.positions[i][k], Endian::Little);
    if (frame.has_velocities())
      for (int k = 0; k < 3; ++k) io::store(out, frame.velocities[i][k], Endian::Little);
    if (frame.has_ids()) io::store(out, frame.ids[i], Endian::Little);
    if (!frame.masses.empty()) io::store(out, frame.masses[i], Endian::Little);
  }
  write_file_atomically(path, [&](std::ostream& s) { s.write(out.data(), std::streamsize(out.size())); });
}

}  // namespace spume
