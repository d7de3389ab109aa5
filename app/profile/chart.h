// A chart drawn with Cairo: anti-aliased lines and shapes, text in fontconfig's sans-serif
// (DejaVu Sans on Debian). Vector SVG when the path ends in .svg; otherwise a raster handed
// to OpenImageIO, so PNG, JPEG, TIFF, ... all work. Coordinates are pixels, y down.
#pragma once

#include <string>
#include <utility>
#include <vector>

typedef struct _cairo cairo_t;
typedef struct _cairo_surface cairo_surface_t;

namespace tessera {

struct Colour {
  double r = 0.0, g = 0.0, b = 0.0;  // sRGB, each in [0, 1]
};
Colour hex_colour(unsigned rgb);  // 0xRRGGBB

struct Font {
  double size = 13.0;  // pixels
  bool bold = false;
};

enum class Align { left, centre, right };  // where the text's anchor is

using Point = std::pair<double, double>;

// True when `path` ends in .svg (any case).
bool is_svg_path(const std::string& path);

// Throws OutputPathError when a chart cannot be written to `path`: an SVG needs a writable
// place, a raster also a format OpenImageIO writes. Call it before the work.
void check_chart_path(const std::string& path);

// Width of `s` in pixels: for laying a chart out before drawing it.
double text_width(const std::string& s, Font font);

// The step of 1, 2 or 5 x 10^k that divides [0, range] into at most `most` intervals, the
// finest such: where axis ticks go.
double tick_step(double range, int most);

// Multiples of `step` from `from` up to `to` (within rounding).
std::vector<double> ticks(double from, double to, double step);

class Chart {
 public:
  // A white chart of width x height pixels, to be written to `path`.
  Chart(const std::string& path, int width, int height);
  ~Chart();
  Chart(const Chart&) = delete;
  Chart& operator=(const Chart&) = delete;

  void rect(double x, double y, double w, double h, Colour fill);
  void outline(double x, double y, double w, double h, Colour stroke, double width = 1.0);
  // `dash` lists on and off lengths; empty for a solid line.
  void polyline(const std::vector<Point>& points, Colour stroke, double width = 1.0,
                const std::vector<double>& dash = {});
  void line(Point from, Point to, Colour stroke, double width = 1.0, const std::vector<double>& dash = {});
  void circle(Point centre, double radius, Colour fill);
  // Evenly spaced colours from the bottom of the rectangle to its top, blended between.
  void vertical_gradient(double x, double y, double w, double h, const std::vector<Colour>& bottom_to_top);
  // `at` is the anchor on the baseline; `degrees` turns the text anticlockwise about it.
  void text(Point at, const std::string& s, Font font, Colour colour, Align align = Align::left,
            double degrees = 0.0);

  // Writes the file atomically (see imageio/file_output.h). Throws OutputError.
  void write();

 private:
  std::string path_;
  int width_, height_;
  bool svg_;
  std::string svg_bytes_;  // the SVG surface writes here, write() writes it out
  cairo_surface_t* surface_;
  cairo_t* cr_;
};

}  // namespace tessera
