#include "sim/io/io_bytes.h"

#include <libdeflate.h>
#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <new>
#include <system_error>

#include "sim/core/out_of_memory.h"

namespace spume::io {

namespace {

// Up to `limit` bytes from the start of the file.
std::string read_prefix(const std::filesystem::path& path, uint64_t limit) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) fail(path.string(), ": no such file");
  if (std::filesystem::is_directory(path, ec)) fail(path.string(), ": is a directory, expected a particle file");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path.string(), ": cannot open for reading");
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0) fail(path.string(), ": cannot determine file size");
  in.seekg(0, std::ios::beg);
  const uint64_t n = std::min<uint64_t>(uint64_t(size), limit);
  std::string bytes = allocating(str("reading ", path.string()), n, [&] { return std::string(size_t(n), '\0'); });
  if (n > 0 && !in.read(bytes.data(), std::streamsize(n))) fail(path.string(), ": read failed");
  return bytes;
}

}  // namespace

std::string read_file_bytes(const std::filesystem::path& path) { return read_prefix(path, UINT64_MAX); }

std::string read_file_head(const std::filesystem::path& path, size_t n) { return read_prefix(path, n); }

std::string read_file_tail(const std::filesystem::path& path, size_t n) {
  const std::string head = read_prefix(path, 0);  // the same checks and errors: exists, a file, readable
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  const std::streamoff size = in.tellg();
  if (size < 0) fail(path.string(), ": cannot determine file size");
  const uint64_t take = std::min<uint64_t>(uint64_t(size), n);
  std::string bytes(size_t(take), '\0');
  in.seekg(std::streamoff(uint64_t(size) - take), std::ios::beg);
  if (take > 0 && !in.read(bytes.data(), std::streamsize(take))) fail(path.string(), ": read failed");
  return bytes;
}

bool has_gzip_magic(std::string_view data) {
  return data.size() >= 2 && uint8_t(data[0]) == 0x1f && uint8_t(data[1]) == 0x8b;
}

namespace {

std::string gunzip_in_memory(std::string_view data, const std::string& where) {
  std::string out;
  // Deflate cannot exceed about 1032:1, so the trailer's size hint is trusted only up to that bound.
  if (data.size() >= 18) {
    const uint64_t hint = load<uint32_t>(data.data() + data.size() - 4, Endian::Little);
    out.reserve(size_t(std::min<uint64_t>(hint, uint64_t(data.size()) * 1032)));
  }
  z_stream zs{};
  if (inflateInit2(&zs, 16 + MAX_WBITS) != Z_OK) fail(where, ": cannot initialise zlib");
  size_t in_pos = 0;
  char chunk[1 << 16];
  int rc = Z_OK;
  while (true) {
    zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data() + in_pos));
    const size_t in_len = std::min<size_t>(data.size() - in_pos, 1u << 30);
    zs.avail_in = uInt(in_len);
    zs.next_out = reinterpret_cast<Bytef*>(chunk);
    zs.avail_out = sizeof(chunk);
    rc = inflate(&zs, Z_NO_FLUSH);
    in_pos += in_len - zs.avail_in;
    out.append(chunk, sizeof(chunk) - zs.avail_out);
    if (rc == Z_STREAM_END) {
      // Another gzip member may follow (gzip(1) concatenation); anything else ends the data.
      if (!has_gzip_magic(data.substr(in_pos))) break;
      inflateReset(&zs);
      continue;
    }
    if (rc == Z_BUF_ERROR && in_pos == data.size()) {
      inflateEnd(&zs);
      fail(where, ": truncated gzip data (the compressed stream ends early after ", out.size(),
           " decompressed bytes)");
    }
    if (rc != Z_OK && rc != Z_BUF_ERROR) {
      const std::string msg = zs.msg ? zs.msg : "unknown error";
      inflateEnd(&zs);
      fail(where, ": corrupt gzip data at compressed offset ", in_pos, ": ", msg);
    }
  }
  inflateEnd(&zs);
  return out;
}

}  // namespace

std::string gunzip(std::string_view data, const std::string& where) {
  return allocating(str("inflating ", where), 0, [&] { return gunzip_in_memory(data, where); });
}

struct PrefixReader::Inflater {
  z_stream zs{};
  std::string input = std::string(size_t(1) << 16, '\0');
  uint64_t consumed = 0;  // compressed bytes inflate has taken, for messages
  Inflater() {
    if (inflateInit2(&zs, 16 + MAX_WBITS) != Z_OK) throw std::bad_alloc();
  }
  ~Inflater() { inflateEnd(&zs); }
};

PrefixReader::PrefixReader(const std::filesystem::path& path) : where_(path.string()) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) fail(where_, ": no such file");
  if (std::filesystem::is_directory(path, ec)) fail(where_, ": is a directory, expected a particle file");
  in_.open(path, std::ios::binary);
  if (!in_) fail(where_, ": cannot open for reading");
  const uint64_t size = std::filesystem::file_size(path, ec);
  if (ec) fail(where_, ": cannot determine file size");
  char magic[2] = {};
  in_.read(magic, 2);
  const std::streamsize got = in_.gcount();
  in_.clear();
  in_.seekg(0);
  if (has_gzip_magic(std::string_view(magic, size_t(got)))) {
    inflater_ = std::make_unique<Inflater>();
    size_bound_ = size * 1032;  // deflate's densest code: 258 bytes from about 2 bits
  } else {
    size_bound_ = size;
  }
}

PrefixReader::~PrefixReader() = default;

std::string_view PrefixReader::first(size_t n) {
  if (out_.size() < n && !ended_)
    allocating(str(inflater_ ? "inflating " : "reading ", where_), 0, [&] { inflater_ ? inflate_to(n) : read_plain(n); });
  return std::string_view(out_).substr(0, n);
}

void PrefixReader::read_plain(size_t n) {
  const size_t old = out_.size();
  const size_t want = size_t(std::min<uint64_t>(std::max<size_t>(n, old + (size_t(1) << 16)), size_bound_)) - old;
  out_.resize(old + want);
  in_.read(out_.data() + old, std::streamsize(want));
  out_.resize(old + size_t(in_.gcount()));
  if (out_.size() < n || size_t(in_.gcount()) < want) ended_ = true;
}

// After a gzip member: does another member follow (gzip(1) concatenation)? Anything else ends the data.
bool PrefixReader::next_member_follows() {
  z_stream& zs = inflater_->zs;
  std::string& input = inflater_->input;
  if (zs.avail_in < 2) {
    const size_t left = zs.avail_in;
    std::memmove(input.data(), zs.next_in, left);
    in_.read(input.data() + left, std::streamsize(input.size() - left));
    zs.next_in = reinterpret_cast<Bytef*>(input.data());
    zs.avail_in = uInt(left + size_t(in_.gcount()));
  }
  return has_gzip_magic(std::string_view(reinterpret_cast<const char*>(zs.next_in), zs.avail_in));
}

void PrefixReader::inflate_to(size_t n) {
  z_stream& zs = inflater_->zs;
  std::string& input = inflater_->input;
  while (out_.size() < n && !ended_) {
    if (zs.avail_in == 0) {
      in_.read(input.data(), std::streamsize(input.size()));
      if (in_.gcount() == 0)
        fail(where_, ": truncated gzip data (the compressed stream ends early after ", out_.size(),
             " decompressed bytes)");
      zs.next_in = reinterpret_cast<Bytef*>(input.data());
      zs.avail_in = uInt(in_.gcount());
    }
    // Room grows geometrically, so memory follows what the stream really holds, not what was asked.
    const size_t old = out_.size();
    const size_t room = std::min<size_t>(n - old, std::max<size_t>(old, size_t(1) << 16));
    out_.resize(old + room);
    zs.next_out = reinterpret_cast<Bytef*>(out_.data() + old);
    zs.avail_out = uInt(room);
    const uInt before = zs.avail_in;
    const int rc = inflate(&zs, Z_NO_FLUSH);
    inflater_->consumed += before - zs.avail_in;
    out_.resize(old + room - zs.avail_out);
    if (rc == Z_STREAM_END) {
      if (next_member_follows()) inflateReset(&zs);
      else ended_ = true;
    } else if (rc != Z_OK && rc != Z_BUF_ERROR) {
      fail(where_, ": corrupt gzip data at compressed offset ", inflater_->consumed, ": ",
           zs.msg ? zs.msg : "unknown error");
    }
  }
}

std::string gzip_compress(std::string_view data) {
  // libdeflate rather than zlib: the same format about twice as fast (the whole buffer at once).
  // Particle floats barely compress past level 1 (measured with zlib: 2M diffuse points, 62.7 MB at
  // level 1 vs 64.1 MB at level 6).
  libdeflate_compressor* compressor = libdeflate_alloc_compressor(1);
  if (!compressor) fail("gzip: cannot allocate a compressor");
  std::string out;
  out.resize(libdeflate_gzip_compress_bound(compressor, data.size()));
  const size_t written = libdeflate_gzip_compress(compressor, data.data(), data.size(), out.data(), out.size());
  libdeflate_free_compressor(compressor);
  if (written == 0) fail("gzip: compression of ", data.size(), " bytes failed");
  out.resize(written);
  return out;
}

std::string zlib_uncompress(std::string_view data, size_t expected_size, const std::string& where) {
  std::string out = allocating(str("decompressing a block of ", where), expected_size,
                               [&] { return std::string(expected_size, '\0'); });
  uLongf out_len = uLongf(expected_size);
  const int rc = uncompress(reinterpret_cast<Bytef*>(out.data()), &out_len,
                            reinterpret_cast<const Bytef*>(data.data()), uLong(data.size()));
  if (rc != Z_OK)
    fail(where, ": corrupt zlib block of ", data.size(), " bytes (zlib error ", rc, ", expected ", expected_size,
         " decompressed bytes)");
  if (out_len != expected_size)
    fail(where, ": zlib block decompressed to ", out_len, " bytes; its header says ", expected_size);
  return out;
}

double load_number(const char* p, NumType t, Endian e) {
  switch (t.kind) {
    case NumType::Float: return t.size == 8 ? load<double>(p, e) : double(load<float>(p, e));
    case NumType::Int:
      switch (t.size) {
        case 1: return double(int8_t(*p));
        case 2: return double(load<int16_t>(p, e));
        case 4: return double(load<int32_t>(p, e));
        default: return double(load<int64_t>(p, e));
      }
    case NumType::UInt:
      switch (t.size) {
        case 1: return double(uint8_t(*p));
        case 2: return double(load<uint16_t>(p, e));
        case 4: return double(load<uint32_t>(p, e));
        default: return double(load<uint64_t>(p, e));
      }
  }
  return 0.0;
}

void TokenReader::skip_space() {
  while (pos_ < data_.size() && std::isspace(static_cast<unsigned char>(data_[pos_]))) ++pos_;
}

bool TokenReader::at_end() {
  skip_space();
  return pos_ >= data_.size();
}

std::string_view TokenReader::next(std::string_view what) {
  skip_space();
  if (pos_ >= data_.size()) fail(where_, ": truncated: the file ends while reading ", what);
  const size_t begin = pos_;
  while (pos_ < data_.size() && !std::isspace(static_cast<unsigned char>(data_[pos_]))) ++pos_;
  return data_.substr(begin, pos_ - begin);
}

double TokenReader::number(std::string_view what) {
  std::string_view tok = next(what);
  const std::string_view shown = tok.substr(0, 40);
  if (!tok.empty() && tok[0] == '+') tok.remove_prefix(1);  // from_chars rejects a leading '+'
  double v = 0.0;
  const auto [end, err] = std::from_chars(tok.data(), tok.data() + tok.size(), v);
  // from_chars reports out-of-range values as errors; strtod turns them into +-inf or 0, and
  // validate() then names an infinite one.
  if (err == std::errc::result_out_of_range && end == tok.data() + tok.size())
    return std::strtod(std::string(tok).c_str(), nullptr);
  if (err != std::errc() || end != tok.data() + tok.size())
    fail(where_, ": expected a number for ", what, ", found '", shown, "'");
  return v;
}

uint32_t to_particle_id(double value, size_t i, const std::string& where) {
  if (!(value >= 0.0 && value <= 4294967295.0 && value == std::floor(value)))
    fail(where, ": particle ", i, " has id ", value, "; ids must be integers in 0 .. 4294967295");
  return uint32_t(value);
}

std::string lower_file_name(const std::filesystem::path& path) {
  std::string name = path.filename().string();
  std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return name;
}

bool ends_with(std::string_view s, std::string_view suffix) {
  return s.size() >= suffix.size() && s.substr(s.size() - suffix.size()) == suffix;
}

}  // namespace spume::io
