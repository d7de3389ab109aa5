#include "app/profile/scaling_plot.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "app/profile/colormap.h"

namespace tessera {

namespace {

constexpr double kWidth = 680, kHeight = 440, kLeft = 64, kRight = 150, kTop = 48, kBottom = 56;
const Colour kInk = hex_colour(0x333333), kGridLine = hex_colour(0xe4e4e4), kIdeal = hex_colour(0x888888),
             kCores = hex_colour(0xaaaaaa);
const Font kTitle{15.0}, kLabel{13.0}, kSmall{11.0};
const std::vector<double> kIdealDash{5, 4}, kCoresDash{2, 3};

struct Axes {
  const ScalingPlot& p;
  double x(double v) const { return kLeft + (v - p.x_min) / (p.x_max - p.x_min) * (kWidth - kLeft - kRight); }
  double y(double v) const { return kHeight - kBottom - v / p.y_max * (kHeight - kTop - kBottom); }
  Point at(Point v) const { return {x(v.first), y(v.second)}; }
};

void draw_grid_and_axes(Chart& c, const Axes& a) {
  const ScalingPlot& p = a.p;
  for (double x : p.x_ticks) {
    c.line({a.x(x), a.y(0)}, {a.x(x), a.y(p.y_max)}, kGridLine);
    c.text({a.x(x), a.y(0) + 18}, fmt::format("{:g}", x), kLabel, kInk, Align::centre);
  }
  for (double y : p.y_ticks) {
    c.line({a.x(p.x_min), a.y(y)}, {a.x(p.x_max), a.y(y)}, kGridLine);
    c.text({a.x(p.x_min) - 8, a.y(y) + 4}, fmt::format("{:g}", y), kLabel, kInk, Align::right);
  }
  c.polyline({{a.x(p.x_min), a.y(p.y_max)}, {a.x(p.x_min), a.y(0)}, {a.x(p.x_max), a.y(0)}}, kInk);
  c.text({(a.x(p.x_min) + a.x(p.x_max)) / 2, kHeight - 14}, p.x_label, kLabel, kInk, Align::centre);
  c.text({22, (a.y(0) + a.y(p.y_max)) / 2}, p.y_label, kLabel, kInk, Align::centre, 90.0);
  if (p.cores >= 1 && p.cores < p.x_max) {
    c.line({a.x(p.cores), a.y(0)}, {a.x(p.cores), a.y(p.y_max)}, kCores, 1.0, kCoresDash);
    c.text({a.x(p.cores) + 4, a.y(p.y_max) + 14}, fmt::format("{} cores", p.cores), kSmall, kInk);
  }
}

void draw_series(Chart& c, const Axes& a, const PlotSeries& s) {
  std::vector<Point> points;
  for (const Point& v : s.points) points.push_back(a.at(v));
  c.polyline(points, s.colour, s.dashed ? 1.0 : 2.0, s.dashed ? kIdealDash : std::vector<double>{});
  if (s.markers)
    for (const Point& at : points) c.circle(at, 3.5, s.colour);
}

void draw_legend(Chart& c, const ScalingPlot& p) {
  const double x = kWidth - kRight + 20;
  double y = kTop + 10;
  for (const PlotSeries& s : p.series) {
    c.line({x, y}, {x + 24, y}, s.colour, s.dashed ? 1.0 : 2.0, s.dashed ? kIdealDash : std::vector<double>{});
    c.text({x + 32, y + 4}, s.name, kLabel, kInk);
    y += 22;
  }
}

}  // namespace

ScalingPlot scaling_plot(const ScalingReport& r) {
  ScalingPlot p;
  const bool ranks = r.ranks_max > 1;
  p.title = fmt::format("{}: speedup against {} ({}x{}, {} spp, {} cores)", r.scene,
                        ranks ? "ranks x threads" : "threads", r.width, r.height, r.spp, r.cores);
  p.x_label = ranks ? "threads in all (ranks x threads per rank)" : "threads";
  p.y_label = "speedup (one-thread time / wall time)";
  const int workers = r.threads_max * r.ranks_max;
  p.x_max = std::max(2.0, static_cast<double>(workers));
  double top = workers;
  for (const ScalingRow& row : r.rows) top = std::max(top, row.speedup);
  p.y_max = std::ceil(top * 1.1);
  p.x_ticks = ticks(p.x_min, p.x_max, std::max(1.0, tick_step(p.x_max - p.x_min, 12)));
  p.y_ticks = ticks(0.0, p.y_max, std::max(1.0, tick_step(p.y_max, 8)));
  // A series per scheduler and rank count (x: the threads of all ranks).
  for (int ranks_of = 1; ranks_of <= r.ranks_max; ++ranks_of)
    for (std::size_t k = 0; k < r.schedulers.size(); ++k) {
      PlotSeries s{ranks_of > 1 ? fmt::format("{}, {} ranks", r.schedulers[k], ranks_of) : r.schedulers[k],
                   category_colour(k + (ranks_of - 1) * r.schedulers.size()), {}};
      for (const ScalingRow& row : r.rows)
        if (row.scheduler == r.schedulers[k] && row.ranks == ranks_of)
          s.points.push_back({row.ranks * row.threads, row.speedup});
      p.series.push_back(std::move(s));
    }
  p.series.push_back({"ideal", kIdeal, {{1.0, 1.0}, {p.x_max, p.x_max}}, true, false});
  p.cores = r.cores;
  return p;
}

void write_scaling_plot(const std::string& path, const ScalingReport& r) {
  const ScalingPlot p = scaling_plot(r);
  const Axes a{p};
  Chart c(path, static_cast<int>(kWidth), static_cast<int>(kHeight));
  c.text({kLeft, 24}, p.title, kTitle, kInk);
  draw_grid_and_axes(c, a);
  // The ideal line first, under the measured ones.
  draw_series(c, a, p.series.back());
  for (std::size_t k = 0; k + 1 < p.series.size(); ++k) draw_series(c, a, p.series[k]);
  draw_legend(c, p);
  c.write();
}

}  // namespace tessera
