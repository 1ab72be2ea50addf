#pragma once
// PNG files via libpng. Writes are atomic (temporary file + rename); every error names the file.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "image.h"

namespace spume {

// 8-bit RGB, no interlace. Creates missing parent directories. Throws Error naming `path`.
void write_png(const std::filesystem::path& path, const ImageRGB8& image);

// Reads 8-bit RGB or RGBA (alpha dropped, not composited); grey, palette and 16-bit files are
// converted to 8-bit RGB. Throws Error naming `path` on a missing, truncated or corrupt file.
ImageRGB8 read_png(const std::filesystem::path& path);

// The same, on bytes already in memory; `name` is used in error messages.
ImageRGB8 decode_png(const uint8_t* data, size_t size, const std::string& name);
std::vector<uint8_t> encode_png(const ImageRGB8& image);

}  // namespace spume
