#pragma once
// Contact sheets for look-dev: equal-size renders laid out in a grid, each captioned with the values
// that made it (e.g. "render.spray.radius=0.01"), written as one image.
#include <string>
#include <vector>

#include "render/image/bitmap_font.h"
#include "render/image/image.h"

namespace spume {

struct ContactTile {
  ImageRGB8 image;
  std::vector<std::string> labels;  // caption lines, top to bottom
};

struct ContactSheetStyle {
  int gutter = 8;                  // px around the sheet and between cells
  int text_scale = 1;              // bitmap font scale of the captions
  Rgb8 background{40, 40, 40};
  Rgb8 text{255, 255, 255};
};

// Tiles fill rows left to right, `columns` to a row (fewer when there are fewer tiles). Each cell is
// the tile's image with a caption strip below it, so captions never cover a rendered pixel: the strip
// holds as many lines as the tile with the most labels, line j drawn with draw_text at
// (cell x, cell y + image height + j * text_height). Cells are as wide as the widest of the image and
// every caption line, so no caption is clipped or runs into its neighbour; images sit at the cell's
// top-left. Cell (row r, column c) starts at (gutter + c * (cell width + gutter),
// gutter + r * (cell height + gutter)); the sheet has a gutter on every side.
// Throws Error when there are no tiles, columns < 1, the gutter is negative, the text scale is not
// 1..kMaxTextScale, a tile is empty or malformed, tiles differ in size (naming the first that
// differs), or the sheet would be too large.
ImageRGB8 make_contact_sheet(const std::vector<ContactTile>& tiles, int columns, const ContactSheetStyle& style = {});

}  // namespace spume
