// A small 8-bit RGB raster for charts drawn by tessera itself (the heat map): filled
// rectangles and text in a built-in 5x7 bitmap font, no font files needed.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace tessera {

using Rgb8 = std::array<std::uint8_t, 3>;

struct Canvas {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // row-major, top row first

  Canvas(int w, int h, Rgb8 background);
  void set(int x, int y, Rgb8 c);
  void fill_rect(int x0, int y0, int x1, int y1, Rgb8 c);  // [x0, x1) x [y0, y1), clipped
  // Text with its top-left corner at (x, y), each font pixel `scale` x `scale`. Letters are
  // drawn as capitals; characters the font lacks are left blank.
  void text(int x, int y, const std::string& s, int scale, Rgb8 c);
};

// Width in pixels of `s` drawn at `scale` (6 font columns per character, the last one blank).
int text_width(const std::string& s, int scale);
constexpr int kFontHeight = 7;

}  // namespace tessera
