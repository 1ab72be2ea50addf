#include "render/image/exr_io.h"

#include <array>
#include <exception>

#include <cpuid.h>
#include <half.h>
#include <immintrin.h>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStdIO.h>
#include <ImfStringAttribute.h>

#include "sim/core/atomic_file.h"
#include "sim/core/error.h"
#include "sim/core/parallel.h"

namespace spume {
namespace {

// zlib's level, fixed so that a file's bytes do not depend on the library's default. Level 1: the
// layers are mostly flat, and higher levels cost time for a few per cent.
constexpr int kZipLevel = 1;

// Round to nearest even, as Imath's half(float) does, with the F16C instruction where the processor
// has it (Imath uses it only when the whole build targets it): a 1080p frame's 29 channels are 60M
// conversions.
__attribute__((target("f16c"))) void to_half_f16c(const float* from, size_t stride, Imath::half* to, size_t n) {
  for (size_t i = 0; i < n; ++i) {  // _cvtss_sh's instruction, without its macro (a C99 literal in clang's)
    const __m128i h = _mm_cvtps_ph(_mm_set_ss(from[i * stride]), _MM_FROUND_TO_NEAREST_INT);
    to[i].setBits(uint16_t(_mm_extract_epi16(h, 0)));
  }
}

// F16C is VEX-encoded: the processor must have it and AVX, and the system must save the vector state
// (XCR0's SSE and AVX bits). By cpuid rather than __builtin_cpu_supports, which clang 14 does not
// know "f16c" for.
bool cpu_has_f16c() {
  unsigned a = 0, b = 0, c = 0, d = 0;
  if (!__get_cpuid(1, &a, &b, &c, &d)) return false;
  if (!(c & bit_F16C) || !(c & bit_AVX) || !(c & bit_OSXSAVE)) return false;
  unsigned low = 0, high = 0;
  __asm__("xgetbv" : "=a"(low), "=d"(high) : "c"(0));
  return (low & 6u) == 6u;
}

const bool kHasF16c = cpu_has_f16c();

void to_half(const float* from, size_t stride, Imath::half* to, size_t n) {
  if (kHasF16c) return to_half_f16c(from, stride, to, n);
  for (size_t i = 0; i < n; ++i) to[i] = Imath::half(from[i * stride]);
}

// Four interleaved channels (an RGBA layer) at once: each pixel's four floats are read once.
__attribute__((target("f16c"))) void rgba_to_half_f16c(const float* from, std::array<Imath::half*, 4> to, size_t n) {
  for (size_t i = 0; i < n; ++i) {
    alignas(8) uint16_t h[4];
    _mm_storel_epi64(reinterpret_cast<__m128i*>(h), _mm_cvtps_ph(_mm_loadu_ps(from + 4 * i), _MM_FROUND_TO_NEAREST_INT));
    for (int c = 0; c < 4; ++c) to[size_t(c)][i].setBits(h[c]);
  }
}

// Channels c..c+3 are one interleaved RGBA array: stride 4, consecutive starts, all HALF.
bool rgba_at(const std::vector<ExrChannel>& channels, size_t c) {
  if (!kHasF16c || c + 4 > channels.size()) return false;
  for (size_t k = 0; k < 4; ++k)
    if (channels[c + k].full_float || channels[c + k].stride != 4 || channels[c + k].first != channels[c].first + k)
      return false;
  return true;
}

}  // namespace

void write_exr(const std::filesystem::path& path, int width, int height, const std::vector<ExrChannel>& channels,
               const ExrStrings& strings) {
  if (width <= 0 || height <= 0) fail(path.string(), ": an EXR of ", width, "x", height, " pixels is empty");
  std::string bytes;
  try {
    Imf::Header header(width, height);
    header.compression() = Imf::ZIP_COMPRESSION;
    header.zipCompressionLevel() = kZipLevel;
    for (const auto& [name, value] : strings) header.insert(name, Imf::StringAttribute(value));
    Imf::FrameBuffer frame;
    // The library writes a slice only in its channel's type: halves are rounded here, a channel at a time.
    const size_t n = size_t(width) * size_t(height);
    std::vector<std::vector<Imath::half>> halves(channels.size());
    for (size_t i = 0; i < channels.size(); ++i) {
      const ExrChannel& c = channels[i];
      header.channels().insert(c.name, Imf::Channel(c.full_float ? Imf::FLOAT : Imf::HALF));
      if (c.full_float) {
        const size_t x_stride = sizeof(float) * c.stride;
        frame.insert(c.name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(const_cast<float*>(c.first)), x_stride,
                                        x_stride * size_t(width)));
        continue;
      }
      if (halves[i].empty()) {  // not yet converted with the RGBA layer it belongs to
        if (rgba_at(channels, i)) {
          std::array<Imath::half*, 4> to;
          for (size_t k = 0; k < 4; ++k) halves[i + k].resize(n), to[k] = halves[i + k].data();
          parallel_for(n, size_t(1) << 16, [&](size_t b, size_t e) {
            std::array<Imath::half*, 4> at = to;
            for (auto& p : at) p += b;
            rgba_to_half_f16c(c.first + 4 * b, at, e - b);
          });
        } else {
          halves[i].resize(n);
          parallel_for(n, size_t(1) << 16, [&](size_t b, size_t e) { to_half(c.first + b * c.stride, c.stride, halves[i].data() + b, e - b); });
        }
      }
      frame.insert(c.name, Imf::Slice(Imf::HALF, reinterpret_cast<char*>(halves[i].data()), sizeof(Imath::half),
                                      sizeof(Imath::half) * size_t(width)));
    }
    Imf::StdOSStream stream;
    Imf::OutputFile file(stream, header);
    file.setFrameBuffer(frame);
    file.writePixels(height);
    bytes = stream.str();
  } catch (const std::exception& e) {
    fail(path.string(), ": writing the EXR failed: ", e.what());
  }
  write_bytes_atomically(path, bytes.data(), bytes.size());
}

std::optional<std::string> read_exr_string(const std::filesystem::path& path, const std::string& name) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return std::nullopt;
  try {
    Imf::InputFile file(path.c_str());
    const auto* value = file.header().findTypedAttribute<Imf::StringAttribute>(name);
    if (value) return value->value();
  } catch (const std::exception&) {
  }
  return std::nullopt;
}

ExrContents read_exr(const std::filesystem::path& path) {
  if (!std::filesystem::is_regular_file(path)) fail(path.string(), ": no such EXR file");
  ExrContents out;
  try {
    Imf::InputFile file(path.c_str());
    const Imf::Header& header = file.header();
    const Imath::Box2i window = header.dataWindow();
    out.width = window.max.x - window.min.x + 1, out.height = window.max.y - window.min.y + 1;
    const size_t n = size_t(out.width) * size_t(out.height);
    Imf::FrameBuffer frame;
    for (auto c = header.channels().begin(); c != header.channels().end(); ++c) {
      std::vector<float>& values = out.channels[c.name()];
      values.resize(n);
      out.full_float[c.name()] = c.channel().type == Imf::FLOAT;
      char* origin = reinterpret_cast<char*>(values.data()) -
                     (ptrdiff_t(window.min.x) + ptrdiff_t(window.min.y) * out.width) * ptrdiff_t(sizeof(float));
      frame.insert(c.name(), Imf::Slice(Imf::FLOAT, origin, sizeof(float), sizeof(float) * size_t(out.width)));
    }
    for (auto a = header.begin(); a != header.end(); ++a)
      if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&a.attribute())) out.strings[a.name()] = s->value();
    switch (header.compression()) {
      case Imf::NO_COMPRESSION: out.compression = "none"; break;
      case Imf::ZIP_COMPRESSION: out.compression = "zip"; break;
      case Imf::ZIPS_COMPRESSION: out.compression = "zips"; break;
      case Imf::PIZ_COMPRESSION: out.compression = "piz"; break;
      default: out.compression = "other"; break;
    }
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    fail(path.string(), ": not a readable OpenEXR file: ", e.what());
  }
  return out;
}

}  // namespace spume
