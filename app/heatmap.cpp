#include "app/heatmap.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "app/colormap.h"
#include "renderer/image_output.h"

namespace tessera {

namespace {

constexpr Rgb8 kPaper{255, 255, 255}, kInk{20, 20, 20}, kGrid{40, 40, 40};
constexpr int kMargin = 16, kFont = 2, kBarWidth = 22;

// A step of 1, 2 or 5 x 10^k giving about four intervals up to `max`.
double nice_step(double max) {
  const double raw = max / 4.0, p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0})
    if (m * p >= raw) return m * p;
  return 10.0 * p;
}

struct Unit {
  double scale;  // seconds to the unit
  const char* name;
};
Unit unit_for(double max_seconds) { return max_seconds >= 1.0 ? Unit{1.0, "s"} : Unit{1e3, "ms"}; }

std::string number(double v) { return v == std::floor(v) ? fmt::format("{:.0f}", v) : fmt::format("{:g}", v); }

struct Layout {
  double zoom;  // map pixels per image pixel
  int map_x, map_y, map_w, map_h;
  int bar_x;
};

Layout layout(const WorkPlanParams& p) {
  // Small frames are enlarged and huge ones reduced, so labels and tiles stay legible.
  const double longest = std::max(p.width, p.height);
  const double zoom = std::clamp(640.0 / longest, 1.0 / 3.0, 8.0);
  Layout l;
  l.zoom = zoom;
  l.map_x = kMargin;
  l.map_y = kMargin + 2 * (kFontHeight * kFont + 6);
  l.map_w = std::max(1, static_cast<int>(std::lround(p.width * zoom)));
  l.map_h = std::max(1, static_cast<int>(std::lround(p.height * zoom)));
  l.bar_x = l.map_x + l.map_w + 20;
  return l;
}

void draw_tiles(Canvas& c, const FrameProfile& profile, const Layout& l, double max_seconds) {
  const std::vector<double> seconds = tile_seconds(profile, TileClock::cpu);
  auto sx = [&](int x) { return l.map_x + static_cast<int>(std::lround(x * l.zoom)); };
  auto sy = [&](int y) { return l.map_y + static_cast<int>(std::lround(y * l.zoom)); };
  const bool outline = profile.plan.params.tile_size * l.zoom >= 8.0;
  for (std::size_t t = 0; t < seconds.size(); ++t) {
    const Tile& r = profile.plan.tiles[t];
    c.fill_rect(sx(r.x0), sy(r.y0), sx(r.x1), sy(r.y1), viridis(max_seconds > 0 ? seconds[t] / max_seconds : 0.0));
    if (!outline) continue;
    c.fill_rect(sx(r.x0), sy(r.y0), sx(r.x1), sy(r.y0) + 1, kGrid);
    c.fill_rect(sx(r.x0), sy(r.y0), sx(r.x0) + 1, sy(r.y1), kGrid);
  }
}

void draw_colour_bar(Canvas& c, const Layout& l, double max_seconds) {
  const int top = l.map_y, bottom = l.map_y + std::max(l.map_h, 120);
  for (int y = top; y < bottom; ++y)
    c.fill_rect(l.bar_x, y, l.bar_x + kBarWidth, y + 1, viridis(double(bottom - 1 - y) / (bottom - 1 - top)));
  if (max_seconds <= 0.0) return;
  const Unit u = unit_for(max_seconds);
  const double max = max_seconds * u.scale, step = nice_step(max);
  for (double v = 0.0; v <= max * (1 + 1e-9); v += step) {
    const int y = bottom - 1 - static_cast<int>(std::lround(v / max * (bottom - 1 - top)));
    c.fill_rect(l.bar_x + kBarWidth, y, l.bar_x + kBarWidth + 6, y + 1, kInk);
    c.text(l.bar_x + kBarWidth + 10, y - kFontHeight * kFont / 2, number(v), kFont, kInk);
  }
  c.text(l.bar_x, top - kFontHeight * kFont - 6, std::string("CPU ") + u.name, kFont, kInk);
}

std::string summary_line(const FrameProfile& p) {
  const std::vector<double> s = tile_seconds(p, TileClock::cpu);
  double total = 0.0;
  for (double v : s) total += v;
  const double max = s.empty() ? 0.0 : *std::max_element(s.begin(), s.end());
  return fmt::format("tile CPU time: max {:.3g} s, mean {:.3g} s; efficiency {:.1f}%, imbalance {:.2f}", max,
                     total / std::max<std::size_t>(1, s.size()), 100.0 * p.balance.efficiency, p.balance.imbalance);
}

}  // namespace

Canvas draw_heatmap(const FrameProfile& profile, const HeatmapParams& params) {
  const Layout l = layout(profile.plan.params);
  const std::string summary = summary_line(profile);
  const int line = kFontHeight * kFont + 6;
  const int width = std::max(l.bar_x + kBarWidth + 10 + text_width("0000.0", kFont) + kMargin,
                             2 * kMargin + std::max(text_width(summary, kFont), text_width(params.title, kFont)));
  const int height = l.map_y + std::max(l.map_h, 120) + line + 2 * kMargin;
  Canvas c(width, height, kPaper);
  const std::vector<double> s = tile_seconds(profile, TileClock::cpu);
  const double max_seconds = s.empty() ? 0.0 : *std::max_element(s.begin(), s.end());
  c.text(kMargin, kMargin, params.title, kFont, kInk);
  draw_tiles(c, profile, l, max_seconds);
  draw_colour_bar(c, l, max_seconds);
  c.text(kMargin, l.map_y + std::max(l.map_h, 120) + kMargin, summary, kFont, kInk);
  return c;
}

void write_heatmap(const std::string& path, const FrameProfile& profile, const HeatmapParams& params) {
  const Canvas c = draw_heatmap(profile, params);
  write_rgb8_image(path, c.width, c.height, c.rgb);
}

}  // namespace tessera
