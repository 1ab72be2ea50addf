// XML VTK reader (.vtu / .vtp) with a minimal tag scanner: only Points and PointData DataArrays matter.
#include <algorithm>
#include <charconv>
#include <memory>
#include <climits>
#include <optional>
#include <utility>

#include "sim/core/error.h"
#include "sim/io/attribute_names.h"
#include "sim/io/io_bytes.h"
#include "sim/io/vtk.h"

namespace spume {
namespace {

using io::Endian;
using io::NumType;
using io::VtkRole;

struct Tag {
  std::string name;
  bool closing = false;
  bool self_closing = false;
  std::vector<std::pair<std::string, std::string>> attrs;
  size_t end = 0;  // offset just past '>'
  std::string attr(std::string_view key, std::string fallback = "") const {
    for (const auto& [k, v] : attrs)
      if (k == key) return v;
    return fallback;
  }
};

class XmlScanner {
 public:
  XmlScanner(std::string_view data, const std::string& where) : data_(data), where_(where) {}

  // The next element tag, skipping text, comments and declarations; nullopt at the end of the input.
  std::optional<Tag> next() {
    while (true) {
      const size_t lt = data_.find('<', pos_);
      if (lt == std::string_view::npos) return std::nullopt;
      pos_ = lt;
      if (starts("<!--")) skip_past("-->");
      else if (starts("<?")) skip_past("?>");
      else if (starts("<!")) skip_past(">");
      else return tag();
    }
  }
  // Text from `from` up to the next '<' (a DataArray's inline content).
  std::string_view text(size_t from) const {
    const size_t lt = data_.find('<', from);
    return data_.substr(from, (lt == std::string_view::npos ? data_.size() : lt) - from);
  }

 private:
  bool starts(std::string_view s) const { return data_.substr(pos_, s.size()) == s; }
  void skip_past(std::string_view s) {
    const size_t at = data_.find(s, pos_);
    if (at == std::string_view::npos) fail(where_, ": malformed XML: '", s, "' missing after offset ", pos_);
    pos_ = at + s.size();
  }
  bool is_space(char c) const { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }
  void spaces() {
    while (pos_ < data_.size() && is_space(data_[pos_])) ++pos_;
  }
  std::string name() {
    const size_t begin = pos_;
    while (pos_ < data_.size() && !is_space(data_[pos_]) && data_[pos_] != '>' && data_[pos_] != '/' && data_[pos_] != '=')
      ++pos_;
    return std::string(data_.substr(begin, pos_ - begin));
  }
  [[noreturn]] void malformed(const char* what) const { fail(where_, ": malformed XML at offset ", pos_, ": ", what); }
  Tag tag() {
    Tag t;
    ++pos_;  // '<'
    if (starts("/")) {
      t.closing = true;
      ++pos_;
    }
    t.name = name();
    if (t.name.empty()) malformed("empty tag name");
    while (true) {
      spaces();
      if (pos_ >= data_.size()) malformed("the file ends inside a tag");
      if (starts("/>")) {
        t.self_closing = true;
        pos_ += 2;
        break;
      }
      if (starts(">")) {
        ++pos_;
        break;
      }
      std::string key = name();
      if (key.empty()) malformed("expected an attribute name");
      spaces();
      if (!starts("=")) malformed("expected '=' after an attribute name");
      ++pos_;
      spaces();
      if (pos_ >= data_.size() || (data_[pos_] != '"' && data_[pos_] != '\'')) malformed("expected a quoted value");
      const char quote = data_[pos_++];
      const size_t close = data_.find(quote, pos_);
      if (close == std::string_view::npos) malformed("unterminated attribute value");
      t.attrs.emplace_back(std::move(key), std::string(data_.substr(pos_, close - pos_)));
      pos_ = close + 1;
    }
    t.end = pos_;
    return t;
  }
  std::string_view data_;
  const std::string& where_;
  size_t pos_ = 0;
};

// A byte source for (compressed) data blocks: raw appended bytes or base64 text.
class Source {
 public:
  virtual ~Source() = default;
  virtual std::string take(size_t n) = 0;
  virtual size_t bound() const = 0;  // at most this many bytes remain
};

class RawSource : public Source {
 public:
  explicit RawSource(io::ByteReader r) : r_(std::move(r)) {}
  std::string take(size_t n) override { return std::string(r_.take(n, "appended data")); }
  size_t bound() const override { return r_.remaining(); }

 private:
  io::ByteReader r_;
};

class Base64Source : public Source {
 public:
  Base64Source(std::string_view text, const std::string& where) : text_(text), where_(where) {}
  std::string take(size_t n) override {
    std::string out = std::move(pending_);
    pending_.clear();
    out.reserve(n + 3);
    while (out.size() < n)
      if (!group(out)) fail(where_, ": truncated base64 data: needed ", n, " bytes");
    if (out.size() > n) {
      pending_ = out.substr(n);
      out.resize(n);
    }
    return out;
  }
  size_t bound() const override { return pending_.size() + (text_.size() - pos_) / 4 * 3 + 3; }

 private:
  // Decodes one 4-character group (padding may end any group, as VTK encodes header and data apart).
  bool group(std::string& out) {
    int vals[4], got = 0, pad = 0;
    while (got < 4 && pos_ < text_.size()) {
      const char c = text_[pos_++];
      if (c == ' ' || c == '\n' || c == '\r' || c == '\t') continue;
      int v = -1;
      if (c >= 'A' && c <= 'Z') v = c - 'A';
      else if (c >= 'a' && c <= 'z') v = c - 'a' + 26;
      else if (c >= '0' && c <= '9') v = c - '0' + 52;
      else if (c == '+') v = 62;
      else if (c == '/') v = 63;
      else if (c == '=' && got >= 2) v = 0, ++pad;
      if (v < 0 || (pad > 0 && c != '=')) fail(where_, ": invalid base64 character '", c, "' at offset ", pos_ - 1);
      vals[got++] = v;
    }
    if (got == 0) return false;
    if (got < 4) fail(where_, ": truncated base64 data (a group of ", got, " characters)");
    const uint32_t bits = uint32_t(vals[0]) << 18 | uint32_t(vals[1]) << 12 | uint32_t(vals[2]) << 6 | uint32_t(vals[3]);
    const char bytes[3] = {char(bits >> 16), char(bits >> 8), char(bits)};
    out.append(bytes, size_t(3 - pad));
    return true;
  }
  std::string_view text_;
  const std::string& where_;
  size_t pos_ = 0;
  std::string pending_;
};

struct Layout {
  Endian endian = Endian::Little;
  size_t header_size = 4;  // UInt32 or UInt64
  bool compressed = false;
};

uint64_t header_word(Source& s, const Layout& l) {
  const std::string b = s.take(l.header_size);
  return l.header_size == 8 ? io::load<uint64_t>(b.data(), l.endian) : io::load<uint32_t>(b.data(), l.endian);
}

// One DataArray's bytes: a size header then the data, or VTK's blocked zlib layout.
std::string read_block(Source& s, const Layout& l, uint64_t expected, const std::string& where, const std::string& name) {
  if (!l.compressed) {
    const uint64_t bytes = header_word(s, l);
    if (bytes != expected)
      fail(where, ": array '", name, "' holds ", bytes, " bytes; its size and the piece's point count need ", expected);
    if (bytes > s.bound()) fail(where, ": truncated: array '", name, "' needs ", bytes, " bytes");
    return s.take(size_t(bytes));
  }
  const uint64_t blocks = header_word(s, l), block_size = header_word(s, l), last = header_word(s, l);
  if (blocks > s.bound() / l.header_size) fail(where, ": corrupt compression header of array '", name, "'");
  std::vector<uint64_t> sizes(blocks);
  uint64_t compressed = 0;
  for (uint64_t& c : sizes) {
    c = header_word(s, l);
    compressed += std::min<uint64_t>(c, UINT32_MAX);
  }
  if (compressed > s.bound()) fail(where, ": truncated: compressed array '", name, "' needs ", compressed, " bytes");
  const uint64_t last_size = last == 0 ? block_size : last;
  if (blocks > 0 && (last_size > block_size || (blocks - 1) > (UINT64_MAX - last_size) / std::max<uint64_t>(block_size, 1)))
    fail(where, ": corrupt compression header of array '", name, "'");
  const uint64_t total = blocks == 0 ? 0 : (blocks - 1) * block_size + last_size;
  if (total != expected)
    fail(where, ": array '", name, "' decompresses to ", total, " bytes; its size and the piece's point count need ", expected);
  // zlib cannot compress more than about 1032:1, so a larger claim is corrupt, not a big allocation:
  // every block is checked before anything is allocated.
  for (uint64_t b = 0; b < blocks; ++b) {
    const uint64_t usize = b + 1 == blocks ? last_size : block_size;
    if (sizes[b] > s.bound() || usize > sizes[b] * 1032 + 64)
      fail(where, ": truncated or corrupt compressed block ", b, " of array '", name, "'");
  }
  std::string out;
  out.reserve(size_t(total));
  for (uint64_t b = 0; b < blocks; ++b) {
    const uint64_t usize = b + 1 == blocks ? last_size : block_size;
    out += io::zlib_uncompress(s.take(size_t(sizes[b])), size_t(usize), where);
  }
  return out;
}

NumType vtu_type(const std::string& name, const std::string& where) {
  static const std::pair<const char*, NumType> table[] = {
      {"Int8", {NumType::Int, 1}},    {"UInt8", {NumType::UInt, 1}},   {"Int16", {NumType::Int, 2}},
      {"UInt16", {NumType::UInt, 2}}, {"Int32", {NumType::Int, 4}},    {"UInt32", {NumType::UInt, 4}},
      {"Int64", {NumType::Int, 8}},   {"UInt64", {NumType::UInt, 8}},  {"Float32", {NumType::Float, 4}},
      {"Float64", {NumType::Float, 8}}};
  for (const auto& [n, t] : table)
    if (name == n) return t;
  fail(where, ": DataArray type '", name, "' is not supported; allowed Int8..Int64, UInt8..UInt64, Float32, Float64");
}

uint64_t number_attr(const Tag& t, const char* key, const char* fallback, const std::string& where) {
  const std::string s = t.attr(key, fallback);
  uint64_t v = 0;
  const auto [end, err] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || err != std::errc() || end != s.data() + s.size())
    fail(where, ": <", t.name, "> attribute ", key, "=\"", s, "\" is not a non-negative integer");
  return v;
}

struct ArrayRef {
  Tag tag;
  std::string_view text;  // inline content
};

struct Piece {
  uint64_t points = 0;
  std::optional<ArrayRef> positions;
  std::vector<ArrayRef> arrays;
};

}  // namespace

FluidFrame read_vtu(const std::filesystem::path& path, std::vector<PointAttribute>* attributes) {
  const std::string where = path.string();
  // XML, so its first bytes (after a byte order mark and blanks) open a tag: anything else is refused
  // before the whole file is read.
  const std::string head = io::read_file_head(path, 4096);
  const size_t text = head.rfind("\xef\xbb\xbf", 0) == 0 ? 3 : 0;
  const size_t open = head.find_first_not_of(" \t\r\n", text);
  if (open == std::string::npos ? head.size() == 4096 : head[open] != '<')
    fail(where, ": not an XML VTK file: it must start with '<?xml' or '<VTKFile'");
  const std::string data = io::read_file_bytes(path);
  XmlScanner xml(data, where);
  Layout layout;
  std::vector<Piece> pieces;
  std::vector<std::string> stack;
  std::optional<size_t> appended;  // offset of the first appended byte, after '_'
  bool raw_appended = true, seen_root = false;

  while (auto t = xml.next()) {
    if (t->closing) {
      if (!stack.empty()) stack.pop_back();
      continue;
    }
    const std::string parent = stack.empty() ? "" : stack.back();
    if (t->name == "VTKFile") {
      seen_root = true;
      const std::string type = t->attr("type");
      if (type != "UnstructuredGrid" && type != "PolyData")
        fail(where, ": VTKFile type \"", type, "\" is not particle data; allowed UnstructuredGrid (.vtu) or PolyData (.vtp)");
      layout.endian = t->attr("byte_order", "LittleEndian") == "BigEndian" ? Endian::Big : Endian::Little;
      const std::string header = t->attr("header_type", "UInt32");
      if (header != "UInt32" && header != "UInt64") fail(where, ": header_type \"", header, "\"; allowed UInt32 or UInt64");
      layout.header_size = header == "UInt64" ? 8 : 4;
      const std::string compressor = t->attr("compressor");
      if (!compressor.empty() && compressor != "vtkZLibDataCompressor")
        fail(where, ": compressor \"", compressor, "\" is not supported; re-export with zlib or no compression ",
             "(ParaView: Save Data, Compressor Type ZLib or None)");
      layout.compressed = !compressor.empty();
    } else if (t->name == "Piece") {
      pieces.push_back({number_attr(*t, "NumberOfPoints", "0", where), std::nullopt, {}});
    } else if (t->name == "DataArray" && !pieces.empty() && (parent == "Points" || parent == "PointData")) {
      ArrayRef a{*t, t->self_closing ? std::string_view() : xml.text(t->end)};
      if (parent == "Points") pieces.back().positions = a;
      else pieces.back().arrays.push_back(a);
    } else if (t->name == "AppendedData") {
      const std::string encoding = t->attr("encoding", "raw");
      if (encoding != "raw" && encoding != "base64") fail(where, ": AppendedData encoding \"", encoding, "\"; allowed raw or base64");
      raw_appended = encoding == "raw";
      const size_t underscore = data.find('_', t->end);
      if (underscore == std::string::npos) fail(where, ": AppendedData has no '_' marker before its data");
      appended = underscore + 1;
      break;  // raw binary follows: the XML scan ends here
    }
    if (!t->self_closing) stack.push_back(t->name);
  }
  if (!seen_root) fail(where, ": not a VTK XML file: no <VTKFile> element");

  auto decode = [&](const ArrayRef& a, uint64_t points, int comps, std::vector<double>& out) {
    const std::string name = a.tag.attr("Name", "Points");
    const NumType type = vtu_type(a.tag.attr("type"), where);
    const std::string format = a.tag.attr("format", "ascii");
    if (points > UINT64_MAX / 8 / uint64_t(comps)) fail(where, ": NumberOfPoints ", points, " is not valid");
    const uint64_t count = points * uint64_t(comps);
    if (format == "ascii") {
      if (count > a.text.size()) fail(where, ": truncated: ascii array '", name, "' needs ", count, " values");
      io::TokenReader tokens(a.text, where);
      out.resize(size_t(count));
      for (double& v : out) v = tokens.number(str("array '", name, "'"));
      if (!tokens.at_end()) fail(where, ": ascii array '", name, "' has more than the ", count, " values its piece needs");
      return;
    }
    std::unique_ptr<Source> src;
    if (format == "binary") {
      src = std::make_unique<Base64Source>(a.text, where);
    } else if (format == "appended") {
      if (!appended) fail(where, ": array '", name, "' is appended but the file has no <AppendedData>");
      const uint64_t offset = number_attr(a.tag, "offset", "", where);
      if (offset > data.size() - *appended) fail(where, ": array '", name, "' offset ", offset, " is past the end of the file");
      const std::string_view rest = std::string_view(data).substr(*appended + size_t(offset));
      if (raw_appended) src = std::make_unique<RawSource>(io::ByteReader(rest, where));
      else src = std::make_unique<Base64Source>(rest, where);
    } else {
      fail(where, ": DataArray format \"", format, "\"; allowed ascii, binary or appended");
    }
    const std::string bytes = read_block(*src, layout, count * type.size, where, name);
    out.resize(size_t(count));
    for (size_t i = 0; i < out.size(); ++i) out[i] = io::load_number(bytes.data() + i * type.size, type, layout.endian);
  };

  FluidFrame frame;
  std::vector<double> values;
  for (size_t pi = 0; pi < pieces.size(); ++pi) {
    const Piece& piece = pieces[pi];
    const size_t first = frame.positions.size();
    if (piece.points == 0) continue;
    if (!piece.positions) fail(where, ": piece ", pi, " has ", piece.points, " points but no <Points> DataArray");
    if (number_attr(piece.positions->tag, "NumberOfComponents", "1", where) != 3)
      fail(where, ": the Points DataArray must have NumberOfComponents=\"3\"");
    decode(*piece.positions, piece.points, 3, values);
    for (size_t i = 0; i < piece.points; ++i) frame.positions.emplace_back(float(values[3 * i]), float(values[3 * i + 1]), float(values[3 * i + 2]));
    bool got_v = false, got_id = false, got_m = false;
    // Pieces are concatenated, so an array must be in every piece or in none.
    auto start = [&](size_t have, const std::string& name) {
      if (have != first) fail(where, ": point array '", name, "' is in piece ", pi, " but not in an earlier piece");
    };
    // Per role, the array of the name the table prefers (io/attribute_names.h).
    const ArrayRef* best[4] = {};  // by VtkRole
    for (const ArrayRef& a : piece.arrays) {
      const uint64_t comps = number_attr(a.tag, "NumberOfComponents", "1", where);
      const VtkRole role = io::vtk_role(a.tag.attr("Name"), int(std::min<uint64_t>(comps, 4)));
      const ArrayRef*& slot = best[int(role)];
      if (role != VtkRole::None &&
          (!slot || io::attribute_preference(a.tag.attr("Name")) < io::attribute_preference(slot->tag.attr("Name"))))
        slot = &a;
    }
    for (const ArrayRef* chosen : {best[int(VtkRole::Velocity)], best[int(VtkRole::Id)], best[int(VtkRole::Mass)]}) {
      if (!chosen) continue;
      const ArrayRef& a = *chosen;
      const uint64_t comps = number_attr(a.tag, "NumberOfComponents", "1", where);
      const VtkRole role = io::vtk_role(a.tag.attr("Name"), int(std::min<uint64_t>(comps, 4)));
      bool& got = role == VtkRole::Velocity ? got_v : role == VtkRole::Id ? got_id : got_m;
      got = true;
      decode(a, piece.points, int(comps), values);
      if (role == VtkRole::Velocity) {
        start(frame.velocities.size(), a.tag.attr("Name"));
        for (size_t i = 0; i < piece.points; ++i) frame.velocities.emplace_back(float(values[3 * i]), float(values[3 * i + 1]), float(values[3 * i + 2]));
      } else if (role == VtkRole::Id) {
        start(frame.ids.size(), a.tag.attr("Name"));
        for (size_t i = 0; i < piece.points; ++i) frame.ids.push_back(io::to_particle_id(values[i], first + i, where));
      } else {
        start(frame.masses.size(), a.tag.attr("Name"));
        for (size_t i = 0; i < piece.points; ++i) frame.masses.push_back(float(values[i]));
      }
    }
    if ((!got_v && !frame.velocities.empty()) || (!got_id && !frame.ids.empty()) || (!got_m && !frame.masses.empty()))
      fail(where, ": piece ", pi, " lacks a velocity, id or mass array that an earlier piece has");
  }
  frame.validate(where);
  if (attributes && !pieces.empty()) {
    attributes->clear();
    for (const ArrayRef& a : pieces.front().arrays)
      attributes->push_back({a.tag.attr("Name"), a.tag.attr("type"), int(number_attr(a.tag, "NumberOfComponents", "1", where))});
  }
  return frame;
}

}  // namespace spume
