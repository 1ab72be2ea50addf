#pragma once
// Houdini's binary JSON (the body of .bgeo and, decompressed, of .bgeo.sc since Houdini 12), read as a
// stream of tokens over bytes in memory. Every read checks the bytes left first, so truncated or corrupt
// input becomes an Error naming the file and the byte offset.
//
// Encoding, as seen in Houdini-written files: the byte 7F then the 4 bytes "NSJb" (a little-endian
// int32; "bJSN" when the writer was big-endian, which sets the byte order of all numbers). Then one
// value. A value is one byte of kind, followed by:
//   '[' ... ']' an array, '{' ... '}' a map (key, value, key, value...), 0x00 null, 0x30 false, 0x31 true,
//   0x10 bool (one byte), 0x11/0x12/0x13/0x14 int8/16/32/64, 0x21/0x22 uint8/16,
//   0x18/0x19/0x1a real16/32/64, 0x27 a string (length, bytes),
//   0x26 a reference to a string defined earlier by 0x2b (id, string; 0x2d forgets an id),
//   0x40 a uniform array: element kind, count, then the packed elements (bools as bits in 32-bit words).
// A length or id is one byte below 0xF1, or 0xF2/0xF4/0xF8 followed by a uint16/uint32/int64.
#include <cstdint>
#include <string>
#include <string_view>
#include <unordered_map>

#include "sim/io/io_bytes.h"

namespace spume::hjson {

enum class Kind { ArrayBegin, ArrayEnd, MapBegin, MapEnd, String, Number, Bool, Null, UniformArray };

// Element kinds of a uniform array (and of scalar numbers).
enum class Scalar { Bool, Int8, Int16, Int32, Int64, UInt8, UInt16, Real16, Real32, Real64 };
const char* to_string(Scalar s);

struct Token {
  Kind kind = Kind::Null;
  size_t offset = 0;        // of the token's first byte
  std::string_view text;    // String
  double number = 0.0;      // Number (64-bit integers beyond 2^53 round; `integer` keeps them)
  int64_t integer = 0;      // Number, when `is_integer`
  bool is_integer = false;
  bool boolean = false;     // Bool
  Scalar element = Scalar::Real32;  // UniformArray
  uint64_t count = 0;               // UniformArray: elements
  std::string_view data;            // UniformArray: the packed elements
};

class Reader {
 public:
  // Checks the magic; `where` names the file in every error.
  Reader(std::string_view bytes, std::string where);
  Reader(std::string&&, std::string) = delete;  // the reader only views its bytes

  const std::string& where() const { return where_; }
  size_t offset() const { return pos_; }
  void seek(size_t offset) { pos_ = offset; }
  bool at_end();  // no value left (string definitions aside)

  Token next();      // the next value token (string definitions are taken in passing)
  Kind peek();       // the kind of the next token, without taking it
  void skip_value(); // one whole value, arrays and maps included

  // The next token, which must be of this kind (`what` names it in the error).
  Token expect(Kind kind, std::string_view what);
  std::string_view string(std::string_view what) { return expect(Kind::String, what).text; }
  // A number that must be an integer in [lo, hi].
  int64_t integer(std::string_view what, int64_t lo, int64_t hi);
  // After '[' or '{': true (and the closing token taken) when the container ends here.
  bool end_of(Kind close);

  // Element i of a uniform array, as double (bools 0/1).
  double element(const Token& uniform, uint64_t i) const;

  template <typename... Parts>
  [[noreturn]] void fail_at(size_t offset, Parts&&... parts) const {
    fail(where_, ": ", std::forward<Parts>(parts)..., " (binary JSON, byte ", offset, ")");
  }

 private:
  uint8_t byte(std::string_view what);
  std::string_view take(uint64_t n, std::string_view what);
  uint64_t length(std::string_view what);
  template <typename T>
  T value(std::string_view what) {
    return io::load<T>(take(sizeof(T), what).data(), endian_);
  }
  void take_definitions();  // string definitions (0x2b) and forgettings (0x2d) before a value

  std::string_view bytes_;
  std::string where_;
  io::Endian endian_ = io::Endian::Little;
  size_t pos_ = 0;
  std::unordered_map<int64_t, std::string_view> strings_;  // defined string ids
};

}  // namespace spume::hjson
