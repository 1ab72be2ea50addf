// Legacy VTK reader and writer.
#include "sim/io/vtk.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <climits>
#include <cstdint>
#include <optional>
#include <ostream>

#include "sim/core/atomic_file.h"
#include "sim/core/error.h"
#include "sim/io/attribute_names.h"
#include "sim/io/io_bytes.h"

namespace spume {
namespace io {

VtkRole vtk_role(std::string_view name, int components) {
  const std::optional<AttributeRole> role = attribute_role(name);
  if (!role) return VtkRole::None;
  if (*role == AttributeRole::Velocity) return components == 3 ? VtkRole::Velocity : VtkRole::None;
  if (components != 1) return VtkRole::None;
  return *role == AttributeRole::Id ? VtkRole::Id : VtkRole::Mass;
}

}  // namespace io

namespace {

using io::Endian;
using io::NumType;
using io::VtkRole;

std::string lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return out;
}

class LegacyParser {
 public:
  LegacyParser(std::string data, std::string where) : data_(std::move(data)), where_(std::move(where)) {}

  const std::string& where() const { return where_; }
  bool at_end() {
    skip_space();
    return pos_ >= data_.size();
  }
  // The next non-blank line, split into words; binary data, if any, starts on the line after it.
  std::vector<std::string> line_words() {
    skip_space();
    const size_t eol = line_end();
    const std::string_view line(data_.data() + pos_, eol - pos_);
    pos_ = std::min(eol + 1, data_.size());
    std::vector<std::string> words;
    io::TokenReader t(line, where_);
    while (!t.at_end()) words.emplace_back(t.next("header"));
    if (words.empty()) fail(where_, ": truncated: the file ends where a section header was expected");
    return words;
  }
  std::string raw_line() {
    const size_t eol = line_end();
    std::string line = data_.substr(pos_, eol - pos_);
    pos_ = std::min(eol + 1, data_.size());
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return line;
  }
  // The next line's words (consumed) when it starts with `keyword`, case-insensitively. In binary
  // files the bytes after a header line may be data, so nothing is consumed on a mismatch.
  std::optional<std::vector<std::string>> next_line_if(std::string_view keyword) {
    const size_t save = pos_;
    skip_space();
    if (lower(std::string_view(data_).substr(pos_, keyword.size())) == keyword) return line_words();
    pos_ = save;
    return std::nullopt;
  }
  void set_binary(bool b) { binary_ = b; }
  bool binary() const { return binary_; }

  // Reads count values (into *out, or skipped when out is null).
  void values(uint64_t count, NumType t, std::vector<double>* out, std::string_view what) {
    if (binary_) {
      io::ByteReader r(std::string_view(data_).substr(pos_), where_, Endian::Big);
      r.require_array(count, t.size, what);
      if (out) {
        out->resize(size_t(count));
        for (size_t i = 0; i < count; ++i) (*out)[i] = io::load_number(data_.data() + pos_ + i * t.size, t, Endian::Big);
      }
      pos_ += size_t(count) * t.size;
      return;
    }
    if (count > data_.size() - pos_)  // every ASCII value takes at least one byte
      fail(where_, ": truncated: ", what, " needs ", count, " values but only ", data_.size() - pos_, " bytes remain");
    io::TokenReader tokens(data_, where_, pos_);
    if (out) out->resize(size_t(count));
    for (size_t i = 0; i < count; ++i) {
      if (out) (*out)[i] = tokens.number(what);
      else tokens.next(what);
    }
    pos_ = tokens.offset();
  }
  // METADATA blocks (VTK >= 8) run to the next blank line.
  void skip_metadata() {
    while (pos_ < data_.size()) {
      const std::string line = raw_line();
      if (line.find_first_not_of(" \t") == std::string::npos) return;
    }
  }

 private:
  // The end of the line at pos_. Keyword lines are short: one that runs on for a megabyte is binary data
  // or damage, refused before it is copied (a file of zeros would otherwise be one line of its size).
  size_t line_end() const {
    constexpr size_t kLongestLine = size_t(1) << 20;
    const size_t eol = std::string_view(data_).substr(pos_, kLongestLine).find('\n');
    if (eol != std::string_view::npos) return pos_ + eol;
    if (data_.size() - pos_ > kLongestLine)
      fail(where_, ": a line at offset ", pos_, " runs past ", kLongestLine, " bytes without a line break, where a ",
           "VTK keyword line belongs (binary data out of place, or not a VTK file)");
    return data_.size();
  }
  void skip_space() {
    while (pos_ < data_.size() && std::isspace(static_cast<unsigned char>(data_[pos_]))) ++pos_;
  }
  std::string data_;
  std::string where_;
  size_t pos_ = 0;
  bool binary_ = false;
};

NumType vtk_type(std::string_view name, const std::string& where) {
  const std::string n = lower(name);
  if (n == "unsigned_char") return {NumType::UInt, 1};
  if (n == "char" || n == "signed_char") return {NumType::Int, 1};
  if (n == "unsigned_short") return {NumType::UInt, 2};
  if (n == "short") return {NumType::Int, 2};
  if (n == "unsigned_int") return {NumType::UInt, 4};
  if (n == "int" || n == "vtkidtype") return {NumType::Int, 4};  // VTK writes vtkIdType arrays as int
  if (n == "unsigned_long" || n == "vtktypeuint64") return {NumType::UInt, 8};
  if (n == "long" || n == "vtktypeint64") return {NumType::Int, 8};
  if (n == "float") return {NumType::Float, 4};
  if (n == "double") return {NumType::Float, 8};
  fail(where, ": VTK data type '", name, "' is not supported; allowed unsigned_char char unsigned_short short ",
       "unsigned_int int unsigned_long long vtktypeint64 vtktypeuint64 float double");
}

uint64_t count_arg(const std::vector<std::string>& w, size_t i, const std::string& where) {
  uint64_t v = 0;
  if (i >= w.size() || std::from_chars(w[i].data(), w[i].data() + w[i].size(), v).ptr != w[i].data() + w[i].size())
    fail(where, ": malformed VTK line '", w.empty() ? "" : w[0], " ...': expected a count as word ", i + 1);
  return v;
}

// The first three lines (version, title, ASCII or BINARY) fit in this many bytes: VTK's own reader
// takes 256 characters a line.
constexpr size_t kHeaderBytes = 3 * 257;

// Checks the version line and that the title and the encoding line end within the first bytes, before
// the whole file is read: anything else is refused on its first bytes, whatever its size.
void check_header_lines(std::string_view head, const std::string& where) {
  const size_t first_end = head.find('\n');
  if (lower(head.substr(0, std::min<size_t>(first_end, 256))).rfind("# vtk datafile version", 0) != 0)
    fail(where, ": not a legacy VTK file: the first line must be '# vtk DataFile Version x.y'");
  const size_t title_end = head.find('\n', first_end + 1);
  if (title_end == std::string_view::npos || head.find('\n', title_end + 1) == std::string_view::npos) {
    if (head.size() < kHeaderBytes)
      fail(where, ": truncated: a legacy VTK file holds a title line and an ASCII or BINARY line after its version line");
    fail(where, ": not a legacy VTK file: its title and its ASCII/BINARY line do not end within its first ",
         kHeaderBytes, " bytes (VTK reads 256 characters a line)");
  }
}

struct PointArrays {
  std::vector<double> positions, velocity, ids, mass;
};

}  // namespace

FluidFrame read_vtk(const std::filesystem::path& path, std::vector<PointAttribute>* attributes) {
  check_header_lines(io::read_file_head(path, kHeaderBytes), path.string());
  LegacyParser p(io::read_file_bytes(path), path.string());
  const std::string& where = p.where();
  p.raw_line();  // the version, checked
  p.raw_line();  // title
  const std::string encoding = lower(p.raw_line());
  if (encoding.rfind("binary", 0) == 0) p.set_binary(true);
  else if (encoding.rfind("ascii", 0) != 0)
    fail(where, ": the third line is '", encoding, "'; a legacy VTK file says ASCII or BINARY there");
  const auto ds = p.line_words();
  if (ds.size() < 2 || lower(ds[0]) != "dataset") fail(where, ": expected 'DATASET <type>' after the ASCII/BINARY line");
  const std::string type = lower(ds[1]);
  if (type != "polydata" && type != "unstructured_grid")
    fail(where, ": DATASET ", ds[1], " is not particle data; allowed POLYDATA or UNSTRUCTURED_GRID");

  FluidFrame frame;
  PointArrays arrays;
  std::vector<PointAttribute> attrs;
  bool have_points = false;
  uint64_t n_points = 0;
  enum class Section { Dataset, Point, Cell } section = Section::Dataset;
  uint64_t section_count = 0;
  auto word = [&](const std::vector<std::string>& w, size_t i) -> const std::string& {
    if (i >= w.size()) fail(where, ": malformed VTK line starting '", w[0], "': missing word ", i + 1);
    return w[i];
  };
  struct {
    size_t velocity = SIZE_MAX, id = SIZE_MAX, mass = SIZE_MAX;
  } preferred;  // the table's place of the name each array was read under
  // Reads one array of comps x tuples values, keeping it when it is a point array spume uses.
  auto array = [&](const std::string& name, const std::string& type_name, NumType t, uint64_t comps, uint64_t tuples) {
    if (comps == 0 || comps > 1024 || tuples > UINT64_MAX / comps)
      fail(where, ": array '", name, "' has ", comps, " components x ", tuples, " tuples; not a valid size");
    std::vector<double>* dst = nullptr;
    if (section == Section::Point) {
      attrs.push_back({name, type_name, int(comps)});
      const VtkRole role = io::vtk_role(name, int(comps));
      std::vector<double>* slot = role == VtkRole::Velocity ? &arrays.velocity
                                  : role == VtkRole::Id     ? &arrays.ids
                                  : role == VtkRole::Mass   ? &arrays.mass
                                                            : nullptr;
      // A name the table prefers replaces one read before it (io/attribute_names.h).
      size_t& best = role == VtkRole::Velocity ? preferred.velocity : role == VtkRole::Id ? preferred.id : preferred.mass;
      if (slot && io::attribute_preference(name) < best) {
        best = io::attribute_preference(name);
        slot->clear();
        dst = slot;
      }
      if (dst && tuples != n_points)
        fail(where, ": point array '", name, "' has ", tuples, " tuples for ", n_points, " points");
    }
    std::vector<double> time;
    if (section == Section::Dataset && name == "TIME" && comps * tuples == 1) dst = &time;
    p.values(comps * tuples, t, dst, name);
    if (!time.empty()) frame.time = time[0];
  };

  while (!p.at_end()) {
    const auto w = p.line_words();
    const std::string kw = lower(w[0]);
    if (kw == "points") {
      if (have_points) fail(where, ": more than one POINTS section");
      n_points = count_arg(w, 1, where);
      if (n_points > UINT64_MAX / 3) fail(where, ": POINTS count ", n_points, " is not valid");
      p.values(3 * n_points, vtk_type(word(w, 2), where), &arrays.positions, "POINTS");
      have_points = true;
    } else if (kw == "vertices" || kw == "lines" || kw == "polygons" || kw == "triangle_strips" || kw == "cells") {
      const uint64_t a = count_arg(w, 1, where), b = count_arg(w, 2, where);
      if (auto off = p.next_line_if("offsets")) {  // VTK 5.1 layout: offsets then connectivity
        p.values(a, vtk_type(word(*off, 1), where), nullptr, "OFFSETS");
        const auto conn = p.line_words();
        if (lower(conn[0]) != "connectivity") fail(where, ": expected CONNECTIVITY after OFFSETS, found '", conn[0], "'");
        p.values(b, vtk_type(word(conn, 1), where), nullptr, "CONNECTIVITY");
      } else {
        p.values(b, {NumType::Int, 4}, nullptr, w[0]);
      }
    } else if (kw == "cell_types") {
      p.values(count_arg(w, 1, where), {NumType::Int, 4}, nullptr, "CELL_TYPES");
    } else if (kw == "point_data" || kw == "cell_data") {
      section = kw == "point_data" ? Section::Point : Section::Cell;
      section_count = count_arg(w, 1, where);
      if (section == Section::Point && section_count != n_points)
        fail(where, ": POINT_DATA ", section_count, " but POINTS ", n_points, "; they must agree");
    } else if (kw == "scalars") {
      const uint64_t comps = w.size() > 3 ? count_arg(w, 3, where) : 1;
      p.next_line_if("lookup_table");  // names the colour table; the values follow it
      array(word(w, 1), word(w, 2), vtk_type(word(w, 2), where), comps, section_count);
    } else if (kw == "vectors" || kw == "normals") {
      array(word(w, 1), word(w, 2), vtk_type(word(w, 2), where), 3, section_count);
    } else if (kw == "texture_coordinates") {
      array(word(w, 1), word(w, 3), vtk_type(word(w, 3), where), count_arg(w, 2, where), section_count);
    } else if (kw == "tensors") {
      array(word(w, 1), word(w, 2), vtk_type(word(w, 2), where), 9, section_count);
    } else if (kw == "color_scalars") {  // bytes in binary files, floats in ASCII ones
      const NumType t = p.binary() ? NumType{NumType::UInt, 1} : NumType{NumType::Float, 4};
      array(word(w, 1), "color", t, count_arg(w, 2, where), section_count);
    } else if (kw == "lookup_table") {
      const uint64_t size = count_arg(w, 2, where);
      if (size > UINT64_MAX / 4) fail(where, ": LOOKUP_TABLE size ", size, " is not valid");
      p.values(4 * size, p.binary() ? NumType{NumType::UInt, 1} : NumType{NumType::Float, 4}, nullptr, "LOOKUP_TABLE");
    } else if (kw == "field") {
      const uint64_t count = count_arg(w, 2, where);
      for (uint64_t i = 0; i < count; ++i) {
        const auto a = p.line_words();
        if (a[0] == "NULL_ARRAY") continue;
        array(a[0], word(a, 3), vtk_type(word(a, 3), where), count_arg(a, 1, where), count_arg(a, 2, where));
        if (p.next_line_if("metadata")) p.skip_metadata();
      }
    } else if (kw == "metadata") {
      p.skip_metadata();
    } else {
      fail(where, ": unknown or unsupported VTK keyword '", w[0], "'");
    }
  }
  if (!have_points) fail(where, ": no POINTS section");

  const size_t n = size_t(n_points);
  frame.positions.resize(n);
  for (size_t i = 0; i < n; ++i)
    frame.positions[i] = Vec3f(float(arrays.positions[3 * i]), float(arrays.positions[3 * i + 1]), float(arrays.positions[3 * i + 2]));
  if (!arrays.velocity.empty()) {
    frame.velocities.resize(n);
    for (size_t i = 0; i < n; ++i)
      frame.velocities[i] = Vec3f(float(arrays.velocity[3 * i]), float(arrays.velocity[3 * i + 1]), float(arrays.velocity[3 * i + 2]));
  }
  if (!arrays.ids.empty()) {
    frame.ids.resize(n);
    for (size_t i = 0; i < n; ++i) frame.ids[i] = io::to_particle_id(arrays.ids[i], i, where);
  }
  frame.masses.assign(arrays.mass.begin(), arrays.mass.end());
  frame.validate(where);
  if (attributes) *attributes = std::move(attrs);
  return frame;
}

void write_vtk(const std::filesystem::path& path, const FluidFrame& frame) {
  frame.validate(path.string());
  const size_t n = frame.size();
  if (n > size_t(INT32_MAX)) fail(path.string(), ": ", n, " points; legacy VTK cells index with int32");
  const Endian be = Endian::Big;
  std::string out = str("# vtk DataFile Version 3.0\nspume fluid frame ", frame.index,
                        "\nBINARY\nDATASET UNSTRUCTURED_GRID\nFIELD FieldData 1\nTIME 1 1 double\n");
  io::store(out, frame.time, be);
  out += str("\nPOINTS ", n, " float\n");
  out.reserve(out.size() + n * 48 + 256);
  for (const Vec3f& x : frame.positions)
    for (int k = 0; k < 3; ++k) io::store(out, x[k], be);
  out += str("\nCELLS ", n, " ", 2 * n, "\n");
  for (size_t i = 0; i < n; ++i) {  // one VTK_VERTEX cell per particle: (1 point, its index)
    io::store(out, int32_t(1), be);
    io::store(out, int32_t(i), be);
  }
  out += str("\nCELL_TYPES ", n, "\n");
  for (size_t i = 0; i < n; ++i) io::store(out, int32_t(1), be);  // VTK_VERTEX
  out += "\n";
  const int fields = int(frame.has_ids()) + int(frame.has_velocities()) + int(!frame.masses.empty());
  if (fields > 0) out += str("POINT_DATA ", n, "\nFIELD FieldData ", fields, "\n");
  if (frame.has_ids()) {
    out += str("id 1 ", n, " unsigned_int\n");
    for (uint32_t id : frame.ids) io::store(out, id, be);
    out += "\n";
  }
  if (frame.has_velocities()) {
    out += str("velocity 3 ", n, " float\n");
    for (const Vec3f& v : frame.velocities)
      for (int k = 0; k < 3; ++k) io::store(out, v[k], be);
    out += "\n";
  }
  if (!frame.masses.empty()) {
    out += str("mass 1 ", n, " float\n");
    for (float m : frame.masses) io::store(out, m, be);
    out += "\n";
  }
  write_file_atomically(path, [&](std::ostream& s) { s.write(out.data(), std::streamsize(out.size())); });
}

}  // namespace spume
