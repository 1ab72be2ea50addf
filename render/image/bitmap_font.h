#pragma once
// A tiny built-in 5x8 bitmap font for labels burnt into images (contact sheets, frame stamps), so
// labelling needs no font files or font library. ASCII 32..126; anything else draws as '?'.
#include <array>
#include <cstdint>
#include <string_view>

#include "render/image/image.h"

namespace spume {

struct Rgb8 {
  uint8_t r = 0, g = 0, b = 0;
};

// Geometry at scale 1; every length is multiplied by the scale. A glyph's ink is 5x8 pixels (row 7
// for descenders only), glyphs advance by 6 (one blank column between them), and a line of text sits
// in a backing box with a one-pixel margin on every side, so boxes of consecutive lines stacked
// kTextLineHeight apart touch.
constexpr int kGlyphWidth = 5;
constexpr int kGlyphHeight = 8;
constexpr int kGlyphAdvance = 6;
constexpr int kTextMargin = 1;
constexpr int kTextLineHeight = kGlyphHeight + 2 * kTextMargin;  // 10
constexpr int kMaxTextScale = 64;

// The 8 rows of a character's glyph, top first; bit 4 (0x10) is the leftmost column.
const std::array<uint8_t, kGlyphHeight>& glyph_rows(char c);

// Size in pixels of the backing box draw_text paints for `text` (0 wide when text is empty).
int text_width(std::string_view text, int scale);
int text_height(int scale);

// Draws one line of text whose backing box has its top-left corner at (x, y). Inside the box the
// picture is dimmed to a quarter (light ink reads on any background, the picture stays faintly
// visible); ink pixels get `colour` exactly. Glyph i's ink starts at
// (x + (kTextMargin + kGlyphAdvance * i) * scale, y + kTextMargin * scale). Clipped to the image.
// Throws Error when scale is outside 1..kMaxTextScale.
void draw_text(ImageRGB8& image, int x, int y, std::string_view text, Rgb8 colour, int scale = 1);

}  // namespace spume
