#pragma once
// PNG files via libpng. Writes are atomic (temporary file + rename); every error names the file.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "render/image/image.h"

namespace spume {

// 8-bit RGB, no interlace. Creates missing parent directories. Throws Error naming `path`.
// `record`, when given, is stored in a tEXt chunk "spume" before the pixels: what the frame was made
// from (the frame record, render/stage/render_stage.h), read back without decoding the image by read_png_record.
void write_png(const std::filesystem::path& path, const ImageRGB8& image, const std::string& record = "");

// The "spume" text of a PNG written by write_png; nullopt for a missing or unreadable file or one
// without it.
std::optional<std::string> read_png_record(const std::filesystem::path& path);

// Reads 8-bit RGB or RGBA (alpha dropped, not composited); grey, palette and 16-bit files are
// converted to 8-bit RGB. Throws Error naming `path` on a missing, truncated or corrupt file.
ImageRGB8 read_png(const std::filesystem::path& path);

// The same, on bytes already in memory; `name` is used in error messages.
ImageRGB8 decode_png(const uint8_t* data, size_t size, const std::string& name);
std::vector<uint8_t> encode_png(const ImageRGB8& image, const std::string& record = "");

}  // namespace spume
