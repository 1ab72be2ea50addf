#include "render/image/png_io.h"

#include <png.h>

#include <csetjmp>
#include <cstring>
#include <fstream>
#include <iterator>
#include <optional>

#include "sim/core/atomic_file.h"
#include "sim/core/error.h"

namespace spume {
namespace {

constexpr const char* kRecordKeyword = "spume";

// libpng reports fatal errors by longjmp. The functions that call setjmp keep only trivially
// destructible locals, and the C++ objects they fill belong to their callers, so a longjmp never
// skips a destructor. The message is copied out here and thrown as an Error by the caller.
struct PngStatus {
  char message[256] = {0};
};

void on_error(png_structp png, png_const_charp msg) {
  auto* status = static_cast<PngStatus*>(png_get_error_ptr(png));
  std::snprintf(status->message, sizeof status->message, "%s", msg ? msg : "unknown libpng error");
  png_longjmp(png, 1);
}
void on_warning(png_structp, png_const_charp) {}  // warnings (e.g. unknown chunks) are not errors

struct MemoryReader {
  const uint8_t* data;
  size_t size, offset;
};

void read_bytes(png_structp png, png_bytep out, png_size_t n) {
  auto* r = static_cast<MemoryReader*>(png_get_io_ptr(png));
  if (n > r->size - r->offset) png_error(png, "file is truncated");
  std::memcpy(out, r->data + r->offset, n);
  r->offset += n;
}

void write_bytes(png_structp png, png_bytep in, png_size_t n) {
  auto* out = static_cast<std::vector<uint8_t>*>(png_get_io_ptr(png));
  out->insert(out->end(), in, in + n);
}
void flush_bytes(png_structp) {}

// Returns false with status->message set on failure. `rows` must hold one pointer per row.
bool encode_rows(const ImageRGB8& image, png_bytep* rows, const std::string* record, std::vector<uint8_t>* out,
                 PngStatus* status) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, status, on_error, on_warning);
  if (!png) return std::snprintf(status->message, sizeof status->message, "out of memory"), false;
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_set_write_fn(png, out, write_bytes, flush_bytes);
  png_set_IHDR(png, info, png_uint_32(image.width), png_uint_32(image.height), 8, PNG_COLOR_TYPE_RGB,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
  // Level 3 is several times faster than the default 6 on 1080p frames for a few percent more bytes.
  png_set_compression_level(png, 3);
  png_text text{};
  if (record && !record->empty()) {
    // Before the image data, so a reader finds it without decoding the pixels.
    text.compression = PNG_TEXT_COMPRESSION_NONE;
    text.key = const_cast<png_charp>(kRecordKeyword);
    text.text = const_cast<png_charp>(record->c_str());
    text.text_length = record->size();
    png_set_text(png, info, &text, 1);
  }
  png_write_info(png, info);
  png_write_image(png, rows);
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return true;
}

// The caller's image and row pointers are sized here, once the header is known.
struct DecodeTarget {
  ImageRGB8* image;
  std::vector<png_bytep>* rows;
};

bool decode_rows(MemoryReader* reader, DecodeTarget target, PngStatus* status) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, status, on_error, on_warning);
  if (!png) return std::snprintf(status->message, sizeof status->message, "out of memory"), false;
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  png_set_read_fn(png, reader, read_bytes);
  png_read_info(png, info);
  const png_uint_32 w = png_get_image_width(png, info), h = png_get_image_height(png, info);
  if (w == 0 || h == 0 || w > 65535 || h > 65535) png_error(png, "image size out of range");
  // A corrupt header may claim up to 65535 x 65535 pixels (12 GB decoded). Deflate expands at most
  // about 1032:1, so a claim the file's bytes cannot hold is refused before anything is allocated.
  if (double(h) * (1.0 + double(png_get_rowbytes(png, info))) > 1100.0 * double(reader->size))
    png_error(png, "the header's image size needs more data than the file holds");
  png_set_expand(png);        // palette -> RGB, grey < 8 bits -> 8 bits, tRNS -> alpha
  png_set_strip_16(png);      // 16-bit -> 8-bit
  png_set_strip_alpha(png);   // RGBA -> RGB: the regression images are opaque
  png_set_gray_to_rgb(png);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  if (png_get_rowbytes(png, info) != png_size_t(w) * 3) png_error(png, "unsupported pixel layout");
  // Resizing vectors here is safe: they belong to the caller and are not destroyed by a longjmp.
  *target.image = ImageRGB8(int(w), int(h));
  target.rows->resize(h);
  for (png_uint_32 y = 0; y < h; ++y) (*target.rows)[y] = target.image->at(0, int(y));
  png_read_image(png, target.rows->data());
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  return true;
}

}  // namespace

std::vector<uint8_t> encode_png(const ImageRGB8& image, const std::string& record) {
  if (image.width <= 0 || image.height <= 0 || image.rgb.size() != image.pixel_count() * 3)
    fail("PNG encode: image is ", image.width, "x", image.height, " with ", image.rgb.size(), " bytes");
  std::vector<png_bytep> rows(size_t(image.height));
  for (int y = 0; y < image.height; ++y) rows[size_t(y)] = const_cast<png_bytep>(image.at(0, y));
  std::vector<uint8_t> out;
  out.reserve(image.rgb.size() / 4 + 1024);
  PngStatus status;
  if (!encode_rows(image, rows.data(), &record, &out, &status)) fail("PNG encode: ", status.message);
  return out;
}

void write_png(const std::filesystem::path& path, const ImageRGB8& image, const std::string& record) {
  const std::vector<uint8_t> bytes = with_context(path.string(), [&] { return encode_png(image, record); });
  write_file_atomically(path, [&](std::ostream& out) { out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size())); });
}

ImageRGB8 decode_png(const uint8_t* data, size_t size, const std::string& name) {
  if (size < 8 || png_sig_cmp(data, 0, 8) != 0) fail(name, ": not a PNG file (bad signature)");
  MemoryReader reader{data, size, 0};
  ImageRGB8 image;
  std::vector<png_bytep> rows;
  PngStatus status;
  if (!decode_rows(&reader, DecodeTarget{&image, &rows}, &status)) fail(name, ": corrupt PNG: ", status.message);
  return image;
}

ImageRGB8 read_png(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path.string(), ": cannot open PNG file for reading");
  const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) fail(path.string(), ": read error");
  return decode_png(bytes.data(), bytes.size(), path.string());
}

std::optional<std::string> read_png_record(const std::filesystem::path& path) {
  // Walk the chunks up to the image data: length (4 bytes, big-endian), type (4), data, CRC (4).
  std::ifstream in(path, std::ios::binary);
  unsigned char signature[8];
  if (!in.read(reinterpret_cast<char*>(signature), 8) || png_sig_cmp(signature, 0, 8) != 0) return std::nullopt;
  for (int chunks = 0; chunks < 64; ++chunks) {
    unsigned char head[8];
    if (!in.read(reinterpret_cast<char*>(head), 8)) return std::nullopt;
    const uint32_t length = uint32_t(head[0]) << 24 | uint32_t(head[1]) << 16 | uint32_t(head[2]) << 8 | head[3];
    const std::string type(reinterpret_cast<char*>(head + 4), 4);
    if (type == "IDAT" || type == "IEND" || length > (1u << 24)) return std::nullopt;
    std::string data(length, '\0');
    if (!in.read(data.data(), std::streamsize(length)) || !in.ignore(4)) return std::nullopt;
    const std::string keyword = std::string(kRecordKeyword) + '\0';
    if (type == "tEXt" && data.compare(0, keyword.size(), keyword) == 0) return data.substr(keyword.size());
  }
  return std::nullopt;
}

}  // namespace spume
