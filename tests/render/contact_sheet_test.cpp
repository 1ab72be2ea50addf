// The bitmap font and contact sheets. Glyph shapes are checked against pictures drawn here by hand,
// tile placement against coordinates worked out by hand from the documented layout.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

#include "sim/core/error.h"
#include "render/image/bitmap_font.h"
#include "render/image/contact_sheet.h"

namespace spume {
namespace {

ImageRGB8 filled(int w, int h, Rgb8 c) {
  ImageRGB8 img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      uint8_t* p = img.at(x, y);
      p[0] = c.r, p[1] = c.g, p[2] = c.b;
    }
  return img;
}

bool is(const ImageRGB8& img, int x, int y, Rgb8 c) {
  const uint8_t* p = img.at(x, y);
  return p[0] == c.r && p[1] == c.g && p[2] == c.b;
}

// Hand-drawn pictures of the intended glyphs, '#' = ink.
// Eight rows: the baseline is under row 6, row 7 holds descenders only.
const std::vector<std::string> kA = {".###.", "#...#", "#...#", "#####", "#...#", "#...#", "#...#", "....."};
const std::vector<std::string> kEquals = {".....", ".....", "#####", ".....", "#####", ".....", ".....", "....."};
const std::vector<std::string> kOne = {"..#..", ".##..", "..#..", "..#..", "..#..", "..#..", ".###.", "....."};
const std::vector<std::string> kG = {".....", ".....", ".####", "#...#", "#...#", ".####", "....#", ".###."};

const Rgb8 kGrey{100, 100, 100}, kDimmed{25, 25, 25}, kInk{255, 240, 0};

// Draws `text` at (x, y) on grey and checks every pixel of the image: outside the backing box grey,
// inside it the glyph pictures (each picture pixel a scale x scale block) in ink, else dimmed grey.
void check_text(const std::string& text, const std::vector<std::vector<std::string>>& pictures, int scale) {
  const int x = 3, y = 2;
  ImageRGB8 img = filled(60 * scale, 15 * scale, kGrey);
  draw_text(img, x, y, text, kInk, scale);
  const int box_w = (6 * int(text.size()) + 1) * scale, box_h = 10 * scale;
  EXPECT_EQ(text_width(text, scale), box_w);
  EXPECT_EQ(text_height(scale), box_h);
  for (int py = 0; py < img.height; ++py)
    for (int px = 0; px < img.width; ++px) {
      const bool in_box = px >= x && px < x + box_w && py >= y && py < y + box_h;
      bool ink = false;
      if (in_box) {
        // Position in font pixels relative to the first glyph's ink origin (x + 1, y + 1) in font pixels.
        const int fx = (px - x) / scale - 1, fy = (py - y) / scale - 1;
        if (fx >= 0 && fy >= 0 && fy < 8 && fx % 6 < 5 && fx / 6 < int(pictures.size()))
          ink = pictures[size_t(fx / 6)][size_t(fy)][size_t(fx % 6)] == '#';
      }
      const Rgb8 want = !in_box ? kGrey : ink ? kInk : kDimmed;
      ASSERT_TRUE(is(img, px, py, want)) << "\"" << text << "\" scale " << scale << " at (" << px << "," << py
                                         << ") expected " << (!in_box ? "background" : ink ? "ink" : "box");
    }
}

TEST(BitmapFont, GlyphInkMatchesHandDrawnPicturesAtScale1And2) {
  for (int scale : {1, 2}) {
    check_text("A", {kA}, scale);
    check_text("A=1g", {kA, kEquals, kOne, kG}, scale);
  }
}

TEST(BitmapFont, EveryPrintableGlyphIsDistinctAndFitsFiveColumns) {
  std::set<std::array<uint8_t, kGlyphHeight>> seen;
  for (int c = 32; c <= 126; ++c) {
    const auto& rows = glyph_rows(char(c));
    for (uint8_t r : rows) EXPECT_LT(r, 32) << "glyph " << char(c);
    EXPECT_TRUE(seen.insert(rows).second) << "glyph '" << char(c) << "' duplicates another";
    bool any_ink = false;
    for (uint8_t r : rows) any_ink |= r != 0;
    EXPECT_EQ(any_ink, c != ' ') << "glyph '" << char(c) << "'";
  }
}

TEST(BitmapFont, CharactersOutsidePrintableAsciiDrawAsQuestionMark) {
  ImageRGB8 a = filled(20, 12, kGrey), b = filled(20, 12, kGrey), c = filled(20, 12, kGrey);
  draw_text(a, 1, 1, "?", kInk, 1);
  draw_text(b, 1, 1, "\x01", kInk, 1);
  draw_text(c, 1, 1, "\xC3", kInk, 1);
  EXPECT_EQ(a.rgb, b.rgb);
  EXPECT_EQ(a.rgb, c.rgb);
}

TEST(BitmapFont, TextIsClippedAtTheImageEdges) {
  // 'A' with its box corner at (-2, -1): ink column c lands at x = -2 + 1 + c, ink row r at y = r.
  ImageRGB8 img = filled(4, 5, kGrey);
  draw_text(img, -2, -1, "A", kInk, 1);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 4; ++x) {
      const int col = x + 1, row = y;
      const bool ink = kA[size_t(row)][size_t(col)] == '#';
      EXPECT_TRUE(is(img, x, y, ink ? kInk : kDimmed)) << x << "," << y;
    }
  // Entirely off the image: nothing changes, nothing breaks.
  ImageRGB8 off = filled(4, 5, kGrey);
  draw_text(off, 100, -50, "off", kInk, 3);
  draw_text(off, -1000000000, 0, "far", kInk, 1);
  EXPECT_EQ(off.rgb, filled(4, 5, kGrey).rgb);
}

TEST(BitmapFont, BadScaleIsAnError) {
  ImageRGB8 img(8, 8);
  EXPECT_THROW(draw_text(img, 0, 0, "x", kInk, 0), Error);
  EXPECT_THROW(draw_text(img, 0, 0, "x", kInk, kMaxTextScale + 1), Error);
}

// Tile k: a plain colour with one marker pixel at (1, 2).
const Rgb8 kMarker{1, 2, 3};
ContactTile tile(int w, int h, uint8_t shade, std::vector<std::string> labels = {}) {
  ContactTile t{filled(w, h, Rgb8{shade, uint8_t(shade + 1), uint8_t(shade + 2)}), std::move(labels)};
  uint8_t* p = t.image.at(1, 2);
  p[0] = kMarker.r, p[1] = kMarker.g, p[2] = kMarker.b;
  return t;
}

TEST(ContactSheet, TilesLandAtHandWorkedCoordinates) {
  // Three 4x3 tiles, 2 columns, gutter 2, no labels: cells are 4x3, the sheet 2 + 2*(4+2) = 14 wide
  // and 2 + 2*(3+2) = 12 high; tiles start at (2,2), (8,2) and (2,7).
  ContactSheetStyle style;
  style.gutter = 2;
  style.background = Rgb8{9, 9, 9};
  const std::vector<ContactTile> tiles = {tile(4, 3, 50), tile(4, 3, 100), tile(4, 3, 150)};
  const ImageRGB8 sheet = make_contact_sheet(tiles, 2, style);
  ASSERT_EQ(sheet.width, 14);
  ASSERT_EQ(sheet.height, 12);
  const int origin[3][2] = {{2, 2}, {8, 2}, {2, 7}};
  for (int y = 0; y < 12; ++y)
    for (int x = 0; x < 14; ++x) {
      Rgb8 want = style.background;
      for (int k = 0; k < 3; ++k) {
        const int tx = x - origin[k][0], ty = y - origin[k][1];
        if (tx < 0 || ty < 0 || tx >= 4 || ty >= 3) continue;
        const uint8_t s = uint8_t(50 * (k + 1));
        want = (tx == 1 && ty == 2) ? kMarker : Rgb8{s, uint8_t(s + 1), uint8_t(s + 2)};
      }
      ASSERT_TRUE(is(sheet, x, y, want)) << x << "," << y;
    }
  // The marker of tile 2 is at sheet (2 + 1, 7 + 2).
  EXPECT_TRUE(is(sheet, 3, 9, kMarker));
}

TEST(ContactSheet, LabelsInkOnlyTheCaptionStripBelowEachImage) {
  // 20x10 tiles, 2 columns, gutter 3. Tile 0 has two caption lines, so every cell's strip holds two
  // lines of 10 px: cells 20 x (10 + 20) = 20x30 ("a=0.5" is 6*5+1 = 31 px wide, so cells widen to 31).
  // Sheet 3 + 2*(31+3) = 71 wide, 3 + 2*(30+3) = 69 high; cells at (3,3), (37,3), (3,36).
  ContactSheetStyle style;
  style.gutter = 3;
  style.background = Rgb8{40, 40, 40};
  style.text = kInk;
  const std::vector<ContactTile> tiles = {tile(20, 10, 60, {"a=0.5", "b=2"}), tile(20, 10, 90, {"a=1"}),
                                          tile(20, 10, 120, {})};
  const ImageRGB8 sheet = make_contact_sheet(tiles, 2, style);
  ASSERT_EQ(sheet.width, 71);
  ASSERT_EQ(sheet.height, 69);
  const int origin[3][2] = {{3, 3}, {37, 3}, {3, 36}};
  for (int k = 0; k < 3; ++k) {
    // Image area untouched by captions.
    const uint8_t s = uint8_t(60 + 30 * k);
    for (int ty = 0; ty < 10; ++ty)
      for (int tx = 0; tx < 20; ++tx) {
        const Rgb8 want = (tx == 1 && ty == 2) ? kMarker : Rgb8{s, uint8_t(s + 1), uint8_t(s + 2)};
        ASSERT_TRUE(is(sheet, origin[k][0] + tx, origin[k][1] + ty, want)) << "tile " << k;
      }
  }
  // Ink appears only inside caption lines that have text: line j of cell k spans
  // [x0, x0 + text width) x [y0 + 10 + 10j, y0 + 20 + 10j).
  struct Box {
    int x0, y0, x1, y1;
  };
  const std::vector<Box> caption = {{3, 13, 3 + 31, 23}, {3, 23, 3 + 19, 33}, {37, 13, 37 + 19, 23}};
  std::vector<int> ink_in(caption.size(), 0);
  for (int y = 0; y < sheet.height; ++y)
    for (int x = 0; x < sheet.width; ++x) {
      if (!is(sheet, x, y, kInk)) continue;
      bool inside = false;
      for (size_t b = 0; b < caption.size(); ++b)
        if (x >= caption[b].x0 && x < caption[b].x1 && y >= caption[b].y0 && y < caption[b].y1) {
          inside = true;
          ++ink_in[b];
        }
      ASSERT_TRUE(inside) << "ink outside every caption line at " << x << "," << y;
    }
  for (size_t b = 0; b < caption.size(); ++b) EXPECT_GT(ink_in[b], 0) << "caption line " << b << " has no ink";
  // 'a' of "a=0.5" in cell 0: its ink origin is (3 + 1, 13 + 1); picture row 2 ".###." inks columns 1-3.
  EXPECT_TRUE(is(sheet, 4 + 1, 14 + 2, kInk));
  EXPECT_TRUE(is(sheet, 4 + 3, 14 + 2, kInk));
  EXPECT_FALSE(is(sheet, 4 + 0, 14 + 2, kInk));
  // Caption box dims the background to a quarter: (40 >> 2) = 10 at the box's corner pixel.
  EXPECT_TRUE(is(sheet, 3, 13, Rgb8{10, 10, 10}));
  // Cell 1's second line and the whole strip of cell 2 keep the plain background.
  EXPECT_TRUE(is(sheet, 37, 23, style.background));
  EXPECT_TRUE(is(sheet, 3, 46, style.background));
}

TEST(ContactSheet, TextScaleWidensCellsAndStrips) {
  // One 8x6 tile, label "xy" at scale 2: (6*2+1)*2 = 26 px wide, 20 px high. Gutter 1:
  // sheet 1 + 26 + 1 = 28 wide, 1 + 6 + 20 + 1 = 28 high.
  ContactSheetStyle style;
  style.gutter = 1;
  style.text_scale = 2;
  const ImageRGB8 sheet = make_contact_sheet({tile(8, 6, 70, {"xy"})}, 3, style);
  EXPECT_EQ(sheet.width, 28);
  EXPECT_EQ(sheet.height, 28);
  EXPECT_TRUE(is(sheet, 1 + 1, 1 + 2, kMarker));
}

TEST(ContactSheet, BadInputIsAnError) {
  auto message = [](const std::vector<ContactTile>& tiles, int columns, ContactSheetStyle style = {}) {
    try {
      make_contact_sheet(tiles, columns, style);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  const std::string sizes = message({tile(4, 3, 10), tile(4, 3, 20), tile(5, 3, 30)}, 2);
  EXPECT_NE(sizes.find("tile 2 is 5x3"), std::string::npos) << sizes;
  EXPECT_NE(sizes.find("tile 0 is 4x3"), std::string::npos) << sizes;
  EXPECT_NE(message({}, 2).find("no tiles"), std::string::npos);
  EXPECT_NE(message({tile(4, 3, 10)}, 0).find("columns must be at least 1, found 0"), std::string::npos);
  ContactSheetStyle negative;
  negative.gutter = -1;
  EXPECT_NE(message({tile(4, 3, 10)}, 1, negative).find("gutter"), std::string::npos);
  EXPECT_NE(message({ContactTile{}}, 1).find("tile 0 is empty"), std::string::npos);
  ContactSheetStyle no_text;
  no_text.text_scale = 0;
  EXPECT_NE(message({tile(4, 3, 10)}, 1, no_text).find("text scale must be 1..64, found 0"), std::string::npos);
  ContactSheetStyle huge_text;
  huge_text.text_scale = 65;
  EXPECT_NE(message({tile(4, 3, 10, {"x"})}, 1, huge_text).find("found 65"), std::string::npos);
}

}  // namespace
}  // namespace spume
