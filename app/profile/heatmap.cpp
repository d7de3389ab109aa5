#include "app/profile/heatmap.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "app/profile/colormap.h"

namespace tessera {

namespace {

const Colour kInk = hex_colour(0x141414), kGrey = hex_colour(0x555555), kGrid = hex_colour(0x282828);
const Font kTitle{15.0, true}, kLabel{12.0}, kSmall{11.0};
constexpr double kMargin = 16, kBarWidth = 18, kTick = 5;

std::string summary_line(const FrameProfile& p, const std::vector<double>& s) {
  double total = 0.0;
  for (double v : s) total += v;
  const double max = s.empty() ? 0.0 : *std::max_element(s.begin(), s.end());
  return fmt::format("tile CPU time: max {:.3g} s, mean {:.3g} s; efficiency {:.1f}%, imbalance {:.2f}", max,
                     total / std::max<std::size_t>(1, s.size()), 100.0 * p.balance.efficiency,
                     p.balance.imbalance);
}

std::string number(double v) { return fmt::format("{:g}", v); }

// Where everything goes, in chart pixels.
struct Layout {
  double zoom;  // chart pixels per frame pixel
  double map_x, map_y, map_w, map_h;
  double bar_x, bar_h;
  double bottom;  // below the x axis' title
  int width, height;
};

Layout layout(const HeatmapPlot& p) {
  Layout l;
  // Small frames are enlarged and huge ones reduced, so labels and tiles stay legible.
  l.zoom = std::clamp(640.0 / std::max(p.width, p.height), 1.0 / 3.0, 8.0);
  l.map_w = std::max(1.0, std::round(p.width * l.zoom));
  l.map_h = std::max(1.0, std::round(p.height * l.zoom));
  l.map_x = kMargin + kLabel.size + 8 + text_width(std::to_string(p.height), kSmall) + kTick + 4;
  l.map_y = kMargin + kTitle.size + 14;
  l.bar_x = l.map_x + l.map_w + 24;
  l.bar_h = std::max(l.map_h, 160.0);
  double labels = 0.0;
  for (double v : p.bar_ticks) labels = std::max(labels, text_width(number(v), kLabel));
  for (const LegendEntry& e : p.legend) labels = std::max(labels, text_width(e.label, kLabel));
  const double legend_right = l.bar_x + kBarWidth + kTick + 4 + labels + 8 + kLabel.size + kMargin;
  l.bottom = l.map_y + std::max(l.map_h + kTick + 2 * kSmall.size + 12, l.bar_h);
  l.width = static_cast<int>(std::ceil(std::max({legend_right, 2 * kMargin + text_width(p.summary, kLabel),
                                                 2 * kMargin + text_width(p.title, kTitle)})));
  l.height = static_cast<int>(std::ceil(l.bottom + 14 + kLabel.size + kMargin));
  return l;
}

void draw_tiles(Chart& c, const HeatmapPlot& p, const Layout& l) {
  auto sx = [&](int x) { return l.map_x + std::round(x * l.zoom); };
  auto sy = [&](int y) { return l.map_y + std::round(y * l.zoom); };
  for (const HeatmapCell& cell : p.cells)
    c.rect(sx(cell.rect.x0), sy(cell.rect.y0), sx(cell.rect.x1) - sx(cell.rect.x0),
           sy(cell.rect.y1) - sy(cell.rect.y0), cell.colour);
  if (!p.cells.empty() && (p.cells[0].rect.x1 - p.cells[0].rect.x0) * l.zoom >= 8.0)
    for (const HeatmapCell& cell : p.cells)  // each tile's top and left edge, on pixel centres
      c.polyline({{sx(cell.rect.x0) + 0.5, sy(cell.rect.y1)},
                  {sx(cell.rect.x0) + 0.5, sy(cell.rect.y0) + 0.5},
                  {sx(cell.rect.x1), sy(cell.rect.y0) + 0.5}},
                 kGrid);
  c.outline(l.map_x - 0.5, l.map_y - 0.5, l.map_w + 1, l.map_h + 1, kInk);
}

// Frame pixel coordinates along the top-left origin: x below the map, y to its left.
void draw_pixel_axes(Chart& c, const HeatmapPlot& p, const Layout& l) {
  const double below = l.map_y + l.map_h;
  for (double x : ticks(0, p.width, tick_step(p.width, 6))) {
    const double at = std::round(l.map_x + x * l.zoom) + 0.5;
    c.line({at, below}, {at, below + kTick}, kGrey);
    c.text({at, below + kTick + kSmall.size}, number(x), kSmall, kGrey, Align::centre);
  }
  for (double y : ticks(0, p.height, tick_step(p.height, 6))) {
    const double at = std::round(l.map_y + y * l.zoom) + 0.5;
    c.line({l.map_x - kTick, at}, {l.map_x, at}, kGrey);
    c.text({l.map_x - kTick - 3, at + 4}, number(y), kSmall, kGrey, Align::right);
  }
  c.text({l.map_x + l.map_w / 2, below + kTick + 2 * kSmall.size + 8}, "x (pixels)", kSmall, kGrey, Align::centre);
  c.text({kMargin + kSmall.size, l.map_y + l.map_h / 2}, "y (pixels)", kSmall, kGrey, Align::centre, 90.0);
}

void draw_colour_bar(Chart& c, const HeatmapPlot& p, const Layout& l) {
  const double top = l.map_y, bottom = l.map_y + l.bar_h, right = l.bar_x + kBarWidth;
  c.vertical_gradient(l.bar_x, top, kBarWidth, l.bar_h, viridis_ramp(33));
  c.outline(l.bar_x - 0.5, top - 0.5, kBarWidth + 1, l.bar_h + 1, kInk);
  double labels = 0.0;
  for (double v : p.bar_ticks) {
    const double y = p.bar_max > 0 ? bottom - v / p.bar_max * l.bar_h : bottom;
    c.line({right, y}, {right + kTick, y}, kInk);
    c.text({right + kTick + 4, y + 4}, number(v), kLabel, kInk);
    labels = std::max(labels, text_width(number(v), kLabel));
  }
  c.text({right + kTick + 4 + labels + 8 + kLabel.size, top + l.bar_h / 2}, p.bar_label, kLabel, kInk, Align::centre,
         90.0);
}

// A swatch and a label per rank, where the colour bar would be.
void draw_legend(Chart& c, const HeatmapPlot& p, const Layout& l) {
  double y = l.map_y;
  for (const LegendEntry& e : p.legend) {
    c.rect(l.bar_x, y, kBarWidth, kBarWidth, e.colour);
    c.outline(l.bar_x - 0.5, y - 0.5, kBarWidth + 1, kBarWidth + 1, kInk);
    c.text({l.bar_x + kBarWidth + 8, y + kBarWidth / 2 + 4}, e.label, kLabel, kInk);
    y += kBarWidth + 8;
  }
}

// Each tile in its rank's colour: categories for a few ranks, else viridis over the rank.
void colour_by_rank(HeatmapPlot& p, const FrameProfile& profile) {
  const int ranks = static_cast<int>(std::max<std::size_t>(1, profile.ranks.size()));
  for (std::size_t i = 0; i < p.cells.size(); ++i) p.cells[i].rank = profile.tile_rank.empty() ? 0 : profile.tile_rank[i];
  p.summary = fmt::format("tile colour: the rank that spent the most CPU time on it; {} rank{}, cluster efficiency {:.1f}%",
                          ranks, ranks == 1 ? "" : "s", 100.0 * profile.balance.efficiency);
  p.bar_ticks.clear();
  if (ranks <= kCategoryColours) {
    for (HeatmapCell& cell : p.cells) cell.colour = category_colour(cell.rank);
    for (int r = 0; r < ranks; ++r) p.legend.push_back({"rank " + std::to_string(r), category_colour(r)});
    return;
  }
  std::vector<double> t;
  for (const HeatmapCell& cell : p.cells) t.push_back(static_cast<double>(cell.rank) / (ranks - 1));
  const std::vector<Colour> colours = viridis(t);
  for (std::size_t i = 0; i < p.cells.size(); ++i) p.cells[i].colour = colours[i];
  p.unit = "rank";
  p.bar_label = "rank";
  p.bar_max = ranks - 1;
  p.bar_ticks = ticks(0, p.bar_max, std::max(1.0, tick_step(p.bar_max, 5)));
}

}  // namespace

HeatmapPlot heatmap_plot(const FrameProfile& profile, const HeatmapParams& params) {
  HeatmapPlot p;
  p.title = params.title;
  p.width = profile.plan.params.width;
  p.height = profile.plan.params.height;
  const std::vector<double> seconds = tile_seconds(profile, TileClock::cpu);
  p.summary = summary_line(profile, seconds);
  const double max = seconds.empty() ? 0.0 : *std::max_element(seconds.begin(), seconds.end());
  std::vector<double> t(seconds.size(), 0.0);
  for (std::size_t i = 0; i < t.size(); ++i) t[i] = max > 0 ? seconds[i] / max : 0.0;
  const std::vector<Colour> colours = viridis(t);
  for (std::size_t i = 0; i < seconds.size(); ++i) p.cells.push_back({profile.plan.tiles[i], seconds[i], colours[i]});
  const double scale = max >= 1.0 ? 1.0 : 1e3;
  p.unit = max >= 1.0 ? "s" : "ms";
  p.bar_max = max * scale;
  if (p.bar_max > 0) p.bar_ticks = ticks(0, p.bar_max, tick_step(p.bar_max, 5));
  p.bar_label = "CPU time per tile (" + p.unit + ")";
  if (params.by == HeatmapBy::rank) colour_by_rank(p, profile);
  return p;
}

void write_heatmap(const std::string& path, const FrameProfile& profile, const HeatmapParams& params) {
  const HeatmapPlot p = heatmap_plot(profile, params);
  const Layout l = layout(p);
  Chart c(path, l.width, l.height);
  c.text({kMargin, kMargin + kTitle.size}, p.title, kTitle, kInk);
  draw_tiles(c, p, l);
  draw_pixel_axes(c, p, l);
  if (p.legend.empty()) draw_colour_bar(c, p, l);
  else draw_legend(c, p, l);
  c.text({kMargin, l.bottom + 14 + kLabel.size}, p.summary, kLabel, kInk);
  c.write();
}

}  // namespace tessera
