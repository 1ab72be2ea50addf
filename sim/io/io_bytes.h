#pragma once
// Byte-level helpers shared by the particle readers and writers: whole-file reads, gzip/zlib, and a
// bounds-checked cursor. Every read checks the remaining length first, so truncated or corrupt input
// becomes an Error naming the file instead of an out-of-bounds read or a huge allocation.
#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <string_view>
#include <type_traits>

#include "sim/core/error.h"

namespace spume::io {

// The whole file as bytes. Throws "<path>: no such file" when it does not exist, and an Error naming the
// file and its size when there is no memory for it.
std::string read_file_bytes(const std::filesystem::path& path);
// Its first n bytes (all of it when shorter): enough to check a magic number or a header before a
// reader takes the whole file. Same errors as read_file_bytes.
std::string read_file_head(const std::filesystem::path& path, size_t n);
// Its last n bytes (all of it when shorter): for formats whose index lies at the end. Same errors.
std::string read_file_tail(const std::filesystem::path& path, size_t n);

bool has_gzip_magic(std::string_view data);
// Decompresses a gzip stream (several concatenated members allowed); `where` names the file in errors.
std::string gunzip(std::string_view data, const std::string& where);
std::string gzip_compress(std::string_view data);
// One zlib (RFC 1950) stream whose decompressed size is known in advance (VTU blocks).
std::string zlib_uncompress(std::string_view data, size_t expected_size, const std::string& where);

// A file's bytes from its start, read (and inflated, when gzip-compressed) only as far as asked: a
// reader checks the magic on the first bytes and takes the body only once its header says how long
// it is, so a huge or hostile file costs no more memory than its header claims (and a claim beyond
// what the file can hold fails before anything is inflated).
class PrefixReader {
 public:
  // Throws "<path>: no such file", "is a directory", "cannot open for reading".
  explicit PrefixReader(const std::filesystem::path& path);
  ~PrefixReader();
  PrefixReader(const PrefixReader&) = delete;
  PrefixReader& operator=(const PrefixReader&) = delete;

  bool gzipped() const { return inflater_ != nullptr; }
  const std::string& where() const { return where_; }
  // The first n bytes, or all there are when the data is shorter. Valid until the next call.
  std::string_view first(size_t n);
  // No more bytes than this can exist: the file's size, or deflate's bound of 1032 times it.
  uint64_t size_bound() const { return size_bound_; }
  // The bytes read so far (at least every byte asked for), moved out.
  std::string release() { return std::move(out_); }

 private:
  struct Inflater;
  void read_plain(size_t n);
  void inflate_to(size_t n);
  bool next_member_follows();

  std::string where_;
  std::ifstream in_;
  uint64_t size_bound_ = 0;
  std::string out_;
  bool ended_ = false;
  std::unique_ptr<Inflater> inflater_;
};

enum class Endian { Little, Big };

template <typename T>
T byteswap_value(T v) {
  static_assert(std::is_trivially_copyable_v<T>);
  char bytes[sizeof(T)];
  std::memcpy(bytes, &v, sizeof(T));
  for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
  std::memcpy(&v, bytes, sizeof(T));
  return v;
}

// Decodes a T stored at p in the given byte order (p need not be aligned).
template <typename T>
T load(const char* p, Endian e) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  const bool native_little = std::endian::native == std::endian::little;
  return (e == Endian::Little) == native_little ? v : byteswap_value(v);
}

// Appends v to out in the given byte order.
template <typename T>
void store(std::string& out, T v, Endian e) {
  const bool native_little = std::endian::native == std::endian::little;
  if ((e == Endian::Little) != native_little) v = byteswap_value(v);
  out.append(reinterpret_cast<const char*>(&v), sizeof(T));
}

// Sequential reader over an in-memory buffer that refuses to read past its end.
class ByteReader {
 public:
  ByteReader(std::string_view data, std::string where, Endian endian = Endian::Little)
      : data_(data), where_(std::move(where)), endian_(endian) {}
  // The reader only views its bytes: a temporary string would dangle.
  ByteReader(std::string&&, std::string, Endian = Endian::Little) = delete;

  size_t offset() const { return pos_; }
  size_t remaining() const { return data_.size() - pos_; }
  bool at_end() const { return pos_ == data_.size(); }
  const std::string& where() const { return where_; }
  std::string_view data() const { return data_; }
  Endian endian() const { return endian_; }
  void set_endian(Endian e) { endian_ = e; }

  // Fails with "truncated" unless n more bytes exist.
  void require(size_t n, std::string_view what) const {
    if (n > remaining())
      fail(where_, ": truncated: ", what, " needs ", n, " bytes at offset ", pos_, " but only ", remaining(),
           " remain");
  }
  // Same for count elements of elem_size bytes, without overflowing count * elem_size.
  void require_array(uint64_t count, size_t elem_size, std::string_view what) const {
    if (elem_size != 0 && count > remaining() / elem_size)
      fail(where_, ": truncated or corrupt: ", what, " claims ", count, " elements of ", elem_size,
           " bytes at offset ", pos_, " but only ", remaining(), " bytes remain");
  }
  std::string_view take(size_t n, std::string_view what) {
    require(n, what);
    std::string_view s = data_.substr(pos_, n);
    pos_ += n;
    return s;
  }
  void skip(size_t n, std::string_view what) { take(n, what); }
  template <typename T>
  T read(std::string_view what) {
    return load<T>(take(sizeof(T), what).data(), endian_);
  }

 private:
  std::string_view data_;
  std::string where_;
  Endian endian_;
  size_t pos_ = 0;
};

// A binary number type as the formats name them (PLY "uchar", VTK "unsigned_int", VTU "Float32"...).
struct NumType {
  enum Kind { Int, UInt, Float } kind = Float;
  size_t size = 4;  // bytes: 1, 2, 4 or 8
};
// Loads the number at p as double (exact for every 32-bit integer; 64-bit ones beyond 2^53 round).
double load_number(const char* p, NumType t, Endian e);

// Whitespace-separated tokens over a buffer, for ASCII bodies (PLY, legacy VTK, VTU ascii arrays).
class TokenReader {
 public:
  TokenReader(std::string_view data, std::string where, size_t pos = 0)
      : data_(data), where_(std::move(where)), pos_(pos) {}
  bool at_end();  // true when only whitespace remains
  std::string_view next(std::string_view what);
  double number(std::string_view what);
  size_t offset() const { return pos_; }
  void set_offset(size_t pos) { pos_ = pos; }

 private:
  void skip_space();
  std::string_view data_;
  std::string where_;
  size_t pos_;
};

// Converts a double read from a file to a particle id, failing (naming `where` and particle i) unless it
// is an integer in 0 .. 2^32-1.
uint32_t to_particle_id(double value, size_t i, const std::string& where);

// "a.b.c" -> lower-case file name, for extension checks that must see ".bgeo.gz" as one suffix.
std::string lower_file_name(const std::filesystem::path& path);
bool ends_with(std::string_view s, std::string_view suffix);

}  // namespace spume::io
