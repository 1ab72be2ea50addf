#include "sim/io/houdini_json.h"

#include <cmath>
#include <limits>

namespace spume::hjson {
namespace {

constexpr uint8_t kNull = 0x00, kBool = 0x10, kInt8 = 0x11, kInt16 = 0x12, kInt32 = 0x13, kInt64 = 0x14,
                  kReal16 = 0x18, kReal32 = 0x19, kReal64 = 0x1a, kUInt8 = 0x21, kUInt16 = 0x22,
                  kTokenRef = 0x26, kString = 0x27, kTokenDef = 0x2b, kValueSeparator = 0x2c, kTokenUndef = 0x2d,
                  kFalse = 0x30, kTrue = 0x31, kKeySeparator = 0x3a, kUniform = 0x40, kArrayBegin = '[',
                  kArrayEnd = ']', kMapBegin = '{', kMapEnd = '}';

bool scalar_of(uint8_t code, Scalar& out) {
  switch (code) {
    case kBool: out = Scalar::Bool; return true;
    case kInt8: out = Scalar::Int8; return true;
    case kInt16: out = Scalar::Int16; return true;
    case kInt32: out = Scalar::Int32; return true;
    case kInt64: out = Scalar::Int64; return true;
    case kUInt8: out = Scalar::UInt8; return true;
    case kUInt16: out = Scalar::UInt16; return true;
    case kReal16: out = Scalar::Real16; return true;
    case kReal32: out = Scalar::Real32; return true;
    case kReal64: out = Scalar::Real64; return true;
  }
  return false;
}

size_t scalar_bytes(Scalar s) {
  switch (s) {
    case Scalar::Bool: return 0;  // bits
    case Scalar::Int8: case Scalar::UInt8: return 1;
    case Scalar::Int16: case Scalar::UInt16: case Scalar::Real16: return 2;
    case Scalar::Int32: case Scalar::Real32: return 4;
    case Scalar::Int64: case Scalar::Real64: return 8;
  }
  return 0;
}

// IEEE 754 half precision to float.
float half_to_float(uint16_t h) {
  const int sign = (h >> 15) & 1, exponent = (h >> 10) & 0x1f, mantissa = h & 0x3ff;
  float magnitude;
  if (exponent == 0) magnitude = std::ldexp(float(mantissa), -24);
  else if (exponent == 31) magnitude = mantissa ? std::numeric_limits<float>::quiet_NaN() : std::numeric_limits<float>::infinity();
  else magnitude = std::ldexp(float(mantissa | 0x400), exponent - 25);
  return sign ? -magnitude : magnitude;
}

const char* kind_name(Kind k) {
  switch (k) {
    case Kind::ArrayBegin: return "an array";
    case Kind::ArrayEnd: return "the end of an array";
    case Kind::MapBegin: return "a map";
    case Kind::MapEnd: return "the end of a map";
    case Kind::String: return "a string";
    case Kind::Number: return "a number";
    case Kind::Bool: return "a boolean";
    case Kind::Null: return "null";
    case Kind::UniformArray: return "a uniform array";
  }
  return "?";
}

}  // namespace

const char* to_string(Scalar s) {
  switch (s) {
    case Scalar::Bool: return "bool";
    case Scalar::Int8: return "int8";
    case Scalar::Int16: return "int16";
    case Scalar::Int32: return "int32";
    case Scalar::Int64: return "int64";
    case Scalar::UInt8: return "uint8";
    case Scalar::UInt16: return "uint16";
    case Scalar::Real16: return "real16";
    case Scalar::Real32: return "real32";
    case Scalar::Real64: return "real64";
  }
  return "?";
}

Reader::Reader(std::string_view bytes, std::string where) : bytes_(bytes), where_(std::move(where)) {
  if (bytes_.size() < 5 || uint8_t(bytes_[0]) != 0x7f)
    fail(where_, ": not Houdini binary JSON geometry: it must start with the byte 7F and 'NSJb'");
  const std::string_view magic = bytes_.substr(1, 4);
  if (magic == "NSJb") endian_ = io::Endian::Little;
  else if (magic == "bJSN") endian_ = io::Endian::Big;
  else fail(where_, ": not Houdini binary JSON geometry: 7F is followed by '", magic, "', expected 'NSJb'");
  pos_ = 5;
}

uint8_t Reader::byte(std::string_view what) { return uint8_t(take(1, what)[0]); }

std::string_view Reader::take(uint64_t n, std::string_view what) {
  if (n > bytes_.size() - pos_)
    fail_at(pos_, "truncated: ", what, " needs ", n, " bytes but only ", bytes_.size() - pos_, " remain");
  const std::string_view out = bytes_.substr(pos_, size_t(n));
  pos_ += size_t(n);
  return out;
}

uint64_t Reader::length(std::string_view what) {
  const size_t at = pos_;
  const uint8_t b = byte(what);
  if (b < 0xf1) return b;
  if (b == 0xf2) return value<uint16_t>(what);
  if (b == 0xf4) return value<uint32_t>(what);
  if (b == 0xf8) {
    const int64_t n = value<int64_t>(what);
    if (n < 0) fail_at(at, what, " is ", n, "; must be >= 0");
    return uint64_t(n);
  }
  fail_at(at, what, " has the length code ", int(b), "; allowed below 241, or 242, 244, 248");
}

void Reader::take_definitions() {
  while (pos_ < bytes_.size()) {
    const uint8_t b = uint8_t(bytes_[pos_]);
    if (b == kTokenDef) {
      ++pos_;
      const int64_t id = int64_t(length("string id"));
      strings_[id] = take(length("defined string length"), "defined string");
    } else if (b == kTokenUndef) {
      ++pos_;
      strings_.erase(int64_t(length("string id")));
    } else if (b == kKeySeparator || b == kValueSeparator) {
      ++pos_;  // separators carry nothing in the binary form
    } else {
      return;
    }
  }
}

bool Reader::at_end() {
  take_definitions();
  return pos_ == bytes_.size();
}

Kind Reader::peek() {
  take_definitions();
  const size_t start = pos_;
  const Kind k = next().kind;
  pos_ = start;
  return k;
}

Token Reader::next() {
  take_definitions();
  Token t;
  t.offset = pos_;
  const uint8_t code = byte("a value");
  Scalar s;
  switch (code) {
    case kArrayBegin: t.kind = Kind::ArrayBegin; return t;
    case kArrayEnd: t.kind = Kind::ArrayEnd; return t;
    case kMapBegin: t.kind = Kind::MapBegin; return t;
    case kMapEnd: t.kind = Kind::MapEnd; return t;
    case kNull: t.kind = Kind::Null; return t;
    case kFalse: case kTrue: t.kind = Kind::Bool; t.boolean = code == kTrue; return t;
    case kString: t.kind = Kind::String; t.text = take(length("string length"), "string"); return t;
    case kTokenRef: {
      const int64_t id = int64_t(length("string id"));
      const auto it = strings_.find(id);
      if (it == strings_.end()) fail_at(t.offset, "refers to string id ", id, ", which was never defined");
      t.kind = Kind::String;
      t.text = it->second;
      return t;
    }
    case kUniform: {
      const size_t at = pos_;
      const uint8_t element = byte("uniform array element kind");
      if (!scalar_of(element, t.element))
        fail_at(at, "uniform array of element kind ", int(element), "; allowed bool, int8..int64, uint8, uint16, real16..real64");
      t.kind = Kind::UniformArray;
      t.count = length("uniform array count");
      const size_t size = scalar_bytes(t.element);
      uint64_t bytes;
      if (t.element == Scalar::Bool) {
        bytes = (t.count / 32 + (t.count % 32 != 0)) * 4;
      } else {
        if (t.count > (bytes_.size() - pos_) / size)
          fail_at(t.offset, "truncated or corrupt: a uniform array claims ", t.count, " ", to_string(t.element),
                  " elements, more than the ", bytes_.size() - pos_, " bytes left hold");
        bytes = t.count * size;
      }
      t.data = take(bytes, "uniform array elements");
      return t;
    }
    default: break;
  }
  if (!scalar_of(code, s)) fail_at(t.offset, "unknown token kind ", int(code), " (file corrupt?)");
  t.kind = s == Scalar::Bool ? Kind::Bool : Kind::Number;
  switch (s) {
    case Scalar::Bool: t.boolean = byte("bool") != 0; return t;
    case Scalar::Int8: t.integer = value<int8_t>("int8"); break;
    case Scalar::Int16: t.integer = value<int16_t>("int16"); break;
    case Scalar::Int32: t.integer = value<int32_t>("int32"); break;
    case Scalar::Int64: t.integer = value<int64_t>("int64"); break;
    case Scalar::UInt8: t.integer = value<uint8_t>("uint8"); break;
    case Scalar::UInt16: t.integer = value<uint16_t>("uint16"); break;
    case Scalar::Real16: t.number = half_to_float(value<uint16_t>("real16")); return t;
    case Scalar::Real32: t.number = value<float>("real32"); return t;
    case Scalar::Real64: t.number = value<double>("real64"); return t;
  }
  t.is_integer = true;
  t.number = double(t.integer);
  return t;
}

void Reader::skip_value() {
  size_t depth = 0;
  do {
    const Token t = next();
    if (t.kind == Kind::ArrayBegin || t.kind == Kind::MapBegin) ++depth;
    else if (t.kind == Kind::ArrayEnd || t.kind == Kind::MapEnd) {
      if (depth == 0) fail_at(t.offset, "found ", kind_name(t.kind), " where a value was expected");
      --depth;
    }
  } while (depth > 0);
}

Token Reader::expect(Kind kind, std::string_view what) {
  const Token t = next();
  if (t.kind != kind) fail_at(t.offset, what, " must be ", kind_name(kind), ", found ", kind_name(t.kind));
  return t;
}

int64_t Reader::integer(std::string_view what, int64_t lo, int64_t hi) {
  const Token t = expect(Kind::Number, what);
  if (!t.is_integer && !(std::floor(t.number) == t.number && std::abs(t.number) < 9e15))
    fail_at(t.offset, what, " is ", t.number, "; must be an integer");
  const int64_t v = t.is_integer ? t.integer : int64_t(t.number);
  if (v < lo || v > hi) fail_at(t.offset, what, " is ", v, "; allowed ", lo, " to ", hi);
  return v;
}

bool Reader::end_of(Kind close) {
  take_definitions();
  if (pos_ >= bytes_.size()) fail_at(pos_, "truncated: the file ends inside ", close == Kind::ArrayEnd ? "an array" : "a map");
  const uint8_t b = uint8_t(bytes_[pos_]);
  if (b == (close == Kind::ArrayEnd ? kArrayEnd : kMapEnd)) {
    ++pos_;
    return true;
  }
  return false;
}

double Reader::element(const Token& u, uint64_t i) const {
  const char* p = u.data.data();
  switch (u.element) {
    case Scalar::Bool: return (io::load<uint32_t>(p + (i / 32) * 4, endian_) >> (i % 32)) & 1u;
    case Scalar::Int8: return io::load<int8_t>(p + i, endian_);
    case Scalar::UInt8: return io::load<uint8_t>(p + i, endian_);
    case Scalar::Int16: return io::load<int16_t>(p + i * 2, endian_);
    case Scalar::UInt16: return io::load<uint16_t>(p + i * 2, endian_);
    case Scalar::Real16: return half_to_float(io::load<uint16_t>(p + i * 2, endian_));
    case Scalar::Int32: return io::load<int32_t>(p + i * 4, endian_);
    case Scalar::Real32: return io::load<float>(p + i * 4, endian_);
    case Scalar::Int64: return double(io::load<int64_t>(p + i * 8, endian_));
    case Scalar::Real64: return io::load<double>(p + i * 8, endian_);
  }
  return 0.0;
}

}  // namespace spume::hjson
