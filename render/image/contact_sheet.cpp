#include "render/image/contact_sheet.h"

#include <algorithm>
#include <cstring>

#include "sim/core/error.h"

namespace spume {
namespace {

// Far beyond any useful sheet (16k x 16k), and small enough that every coordinate fits an int.
constexpr int64_t kMaxSheetPixels = int64_t(1) << 28;

void check_tiles(const std::vector<ContactTile>& tiles, int columns, const ContactSheetStyle& style) {
  if (tiles.empty()) fail("contact sheet: no tiles to lay out");
  if (columns < 1) fail("contact sheet: columns must be at least 1, found ", columns);
  if (style.gutter < 0) fail("contact sheet: gutter must be >= 0 px, found ", style.gutter);
  if (style.text_scale < 1 || style.text_scale > kMaxTextScale)
    fail("contact sheet: text scale must be 1..", kMaxTextScale, ", found ", style.text_scale);
  const ImageRGB8& first = tiles.front().image;
  for (size_t i = 0; i < tiles.size(); ++i) {
    const ImageRGB8& img = tiles[i].image;
    if (img.width < 1 || img.height < 1)
      fail("contact sheet: tile ", i, " is empty (", img.width, "x", img.height, ")");
    if (img.rgb.size() != img.pixel_count() * 3)
      fail("contact sheet: tile ", i, " holds ", img.rgb.size(), " bytes, expected ", img.pixel_count() * 3,
           " for ", img.width, "x", img.height);
    if (img.width != first.width || img.height != first.height)
      fail("contact sheet: tile ", i, " is ", img.width, "x", img.height, " but tile 0 is ", first.width, "x",
           first.height, "; all tiles must have the same size");
  }
}

}  // namespace

ImageRGB8 make_contact_sheet(const std::vector<ContactTile>& tiles, int columns, const ContactSheetStyle& style) {
  check_tiles(tiles, columns, style);
  const int tile_w = tiles.front().image.width, tile_h = tiles.front().image.height;
  const int line_h = text_height(style.text_scale);

  size_t caption_lines = 0;
  int64_t cell_w = tile_w;
  for (const ContactTile& tile : tiles) {
    caption_lines = std::max(caption_lines, tile.labels.size());
    for (const std::string& label : tile.labels)
      cell_w = std::max<int64_t>(cell_w, text_width(label, style.text_scale));
  }
  const int64_t cell_h = tile_h + int64_t(caption_lines) * line_h;
  const int64_t n = int64_t(tiles.size());
  const int64_t cols = std::min<int64_t>(columns, n), rows = (n + columns - 1) / columns;
  const int64_t sheet_w = style.gutter + cols * (cell_w + style.gutter);
  const int64_t sheet_h = style.gutter + rows * (cell_h + style.gutter);
  if (sheet_w * sheet_h > kMaxSheetPixels || sheet_w > kMaxSheetPixels || sheet_h > kMaxSheetPixels)
    fail("contact sheet: ", sheet_w, "x", sheet_h, " px is too large (at most ", kMaxSheetPixels,
         " pixels); use fewer tiles, smaller tiles or shorter labels");

  ImageRGB8 sheet{int(sheet_w), int(sheet_h)};
  for (size_t i = 0; i < sheet.pixel_count(); ++i) {
    sheet.rgb[3 * i] = style.background.r, sheet.rgb[3 * i + 1] = style.background.g;
    sheet.rgb[3 * i + 2] = style.background.b;
  }
  for (int64_t k = 0; k < n; ++k) {
    const ContactTile& tile = tiles[size_t(k)];
    const int x0 = int(style.gutter + (k % columns) * (cell_w + style.gutter));
    const int y0 = int(style.gutter + (k / columns) * (cell_h + style.gutter));
    for (int y = 0; y < tile_h; ++y)
      std::memcpy(sheet.at(x0, y0 + y), tile.image.at(0, y), size_t(tile_w) * 3);
    for (size_t j = 0; j < tile.labels.size(); ++j)
      draw_text(sheet, x0, y0 + tile_h + int(j) * line_h, tile.labels[j], style.text, style.text_scale);
  }
  return sheet;
}

}  // namespace spume
