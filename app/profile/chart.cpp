#include "app/profile/chart.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>

#include <cairo-svg.h>
#include <cairo.h>

#include "imageio/file_output.h"
#include "imageio/image_codec.h"
#include "imageio/image_output.h"

namespace tessera {

namespace {

void set_colour(cairo_t* cr, Colour c) { cairo_set_source_rgb(cr, c.r, c.g, c.b); }

void set_font(cairo_t* cr, Font f) {
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL,
                         f.bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, f.size);
}

void stroke(cairo_t* cr, Colour c, double width, const std::vector<double>& dash) {
  set_colour(cr, c);
  cairo_set_line_width(cr, width);
  cairo_set_dash(cr, dash.data(), static_cast<int>(dash.size()), 0.0);
  cairo_stroke(cr);
}

cairo_status_t append_svg(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

// Cairo's ARGB32 is premultiplied native-endian 0xAARRGGBB; the chart is opaque.
std::vector<std::uint8_t> to_rgb8(cairo_surface_t* s, int width, int height) {
  cairo_surface_flush(s);
  const unsigned char* data = cairo_image_surface_get_data(s);
  const int stride = cairo_image_surface_get_stride(s);
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(width) * height * 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::uint32_t p = *reinterpret_cast<const std::uint32_t*>(data + y * stride + x * 4);
      std::uint8_t* out = &rgb[(static_cast<std::size_t>(y) * width + x) * 3];
      out[0] = (p >> 16) & 0xff;
      out[1] = (p >> 8) & 0xff;
      out[2] = p & 0xff;
    }
  return rgb;
}

}  // namespace

Colour hex_colour(unsigned rgb) {
  return {((rgb >> 16) & 0xff) / 255.0, ((rgb >> 8) & 0xff) / 255.0, (rgb & 0xff) / 255.0};
}

bool is_svg_path(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == ".svg";
}

void check_chart_path(const std::string& path) {
  // A raster chart is written, and the heat map's colours made (viridis), by the image module:
  // loaded here, before the work, so that a missing module fails before anything is rendered.
  if (is_svg_path(path)) check_writable_path(path), (void)image_codec();
  else check_output_path(path);
}

double text_width(const std::string& s, Font font) {
  static cairo_surface_t* scratch = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, 1, 1);
  cairo_t* cr = cairo_create(scratch);
  set_font(cr, font);
  cairo_text_extents_t e;
  cairo_text_extents(cr, s.c_str(), &e);
  cairo_destroy(cr);
  return e.x_advance;
}

double tick_step(double range, int most) {
  if (!(range > 0.0)) return 1.0;
  const double p = std::pow(10.0, std::floor(std::log10(range / most)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (range / (m * p) <= most * (1 + 1e-9)) return m * p;
  return 10.0 * p;
}

std::vector<double> ticks(double from, double to, double step) {
  std::vector<double> out;
  for (double k = std::ceil(from / step - 1e-9); k * step <= to + step * 1e-9; ++k)
    out.push_back(k * step + 0.0);  // + 0.0: no "-0" label
  return out;
}

Chart::Chart(const std::string& path, int width, int height)
    : path_(path), width_(width), height_(height), svg_(is_svg_path(path)) {
  if (svg_) {
    surface_ = cairo_svg_surface_create_for_stream(append_svg, &svg_bytes_, width, height);
    cairo_svg_surface_set_document_unit(surface_, CAIRO_SVG_UNIT_PX);
  } else {
    surface_ = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, width, height);
  }
  cr_ = cairo_create(surface_);
  rect(0, 0, width, height, {1.0, 1.0, 1.0});
}

Chart::~Chart() {
  cairo_destroy(cr_);
  cairo_surface_destroy(surface_);
}

void Chart::rect(double x, double y, double w, double h, Colour fill) {
  cairo_rectangle(cr_, x, y, w, h);
  set_colour(cr_, fill);
  cairo_fill(cr_);
}

void Chart::outline(double x, double y, double w, double h, Colour c, double width) {
  cairo_rectangle(cr_, x, y, w, h);
  stroke(cr_, c, width, {});
}

void Chart::polyline(const std::vector<Point>& points, Colour c, double width, const std::vector<double>& dash) {
  if (points.empty()) return;
  cairo_move_to(cr_, points[0].first, points[0].second);
  for (std::size_t i = 1; i < points.size(); ++i) cairo_line_to(cr_, points[i].first, points[i].second);
  cairo_set_line_join(cr_, CAIRO_LINE_JOIN_ROUND);
  stroke(cr_, c, width, dash);
}

void Chart::line(Point from, Point to, Colour c, double width, const std::vector<double>& dash) {
  polyline({from, to}, c, width, dash);
}

void Chart::circle(Point centre, double radius, Colour fill) {
  cairo_new_sub_path(cr_);
  cairo_arc(cr_, centre.first, centre.second, radius, 0.0, 2.0 * M_PI);
  set_colour(cr_, fill);
  cairo_fill(cr_);
}

void Chart::vertical_gradient(double x, double y, double w, double h, const std::vector<Colour>& bottom_to_top) {
  cairo_pattern_t* g = cairo_pattern_create_linear(0.0, y + h, 0.0, y);
  const double n = std::max<std::size_t>(1, bottom_to_top.size() - 1);
  for (std::size_t i = 0; i < bottom_to_top.size(); ++i) {
    const Colour c = bottom_to_top[i];
    cairo_pattern_add_color_stop_rgb(g, i / n, c.r, c.g, c.b);
  }
  cairo_rectangle(cr_, x, y, w, h);
  cairo_set_source(cr_, g);
  cairo_fill(cr_);
  cairo_pattern_destroy(g);
}

void Chart::text(Point at, const std::string& s, Font font, Colour colour, Align align, double degrees) {
  cairo_save(cr_);
  set_font(cr_, font);
  cairo_translate(cr_, at.first, at.second);
  cairo_rotate(cr_, -degrees * M_PI / 180.0);
  cairo_text_extents_t e;
  cairo_text_extents(cr_, s.c_str(), &e);
  const double shift = align == Align::left ? 0.0 : align == Align::centre ? e.x_advance / 2 : e.x_advance;
  cairo_move_to(cr_, -shift, 0.0);
  set_colour(cr_, colour);
  cairo_show_text(cr_, s.c_str());
  cairo_restore(cr_);
}

void Chart::write() {
  if (svg_) {
    cairo_surface_finish(surface_);  // flushes the document into svg_bytes_
    if (cairo_surface_status(surface_) != CAIRO_STATUS_SUCCESS)
      throw OutputError(path_ + ": " + cairo_status_to_string(cairo_surface_status(surface_)));
    write_text_file(path_, svg_bytes_);
  } else {
    write_rgb8_image(path_, width_, height_, to_rgb8(surface_, width_, height_));
  }
}

}  // namespace tessera
