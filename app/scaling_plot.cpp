// The speedup plot of tessera scaling as a hand-written SVG: axes with ticks and labels,
// the ideal line, a dashed mark at the core count, one line with markers per scheduler.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "app/scaling_report.h"

namespace tessera {

namespace {

constexpr double kWidth = 680, kHeight = 440, kLeft = 64, kRight = 150, kTop = 48, kBottom = 56;
// Okabe-Ito colours: distinguishable by colour-blind readers.
constexpr const char* kColours[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9"};

struct Axes {
  double x_min, x_max, y_max;
  double px(double x) const { return kLeft + (x - x_min) / (x_max - x_min) * (kWidth - kLeft - kRight); }
  double py(double y) const { return kHeight - kBottom - y / y_max * (kHeight - kTop - kBottom); }
};

// The smallest step of 1, 2 or 5 x 10^k that needs at most `most` ticks over `range`.
double tick_step(double range, int most) {
  for (double p = 1.0;; p *= 10.0)
    for (double m : {1.0, 2.0, 5.0})
      if (range / (m * p) <= most) return m * p;
}

std::string xml_escape(const std::string& in) {
  std::string out;
  for (char c : in) out += c == '&' ? "&amp;" : c == '<' ? "&lt;" : c == '>' ? "&gt;" : std::string(1, c);
  return out;
}

std::string text(double x, double y, const std::string& s, const char* anchor = "middle", int size = 13) {
  return fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"{}\" font-size=\"{}\">{}</text>\n", x, y, anchor,
                     size, s);
}

std::string line(double x0, double y0, double x1, double y1, const std::string& style) {
  return fmt::format("<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" {}/>\n", x0, y0, x1, y1, style);
}

std::string grid_and_ticks(const Axes& a) {
  std::string s;
  const double xs = tick_step(a.x_max - 1, 12), ys = tick_step(a.y_max, 8);
  for (double x = 1; x <= a.x_max + 1e-9; x += xs) {
    s += line(a.px(x), a.py(0), a.px(x), a.py(a.y_max), "stroke=\"#e4e4e4\"");
    s += text(a.px(x), a.py(0) + 18, fmt::format("{:g}", x));
  }
  for (double y = 0; y <= a.y_max + 1e-9; y += ys) {
    s += line(a.px(a.x_min), a.py(y), a.px(a.x_max), a.py(y), "stroke=\"#e4e4e4\"");
    s += text(a.px(a.x_min) - 8, a.py(y) + 4, fmt::format("{:g}", y), "end");
  }
  s += line(a.px(a.x_min), a.py(0), a.px(a.x_max), a.py(0), "stroke=\"#333\"");
  s += line(a.px(a.x_min), a.py(0), a.px(a.x_min), a.py(a.y_max), "stroke=\"#333\"");
  s += text((a.px(a.x_min) + a.px(a.x_max)) / 2, kHeight - 14, "threads");
  s += fmt::format("<text transform=\"translate(18 {:.1f}) rotate(-90)\" text-anchor=\"middle\" font-size=\"13\">"
                   "speedup</text>\n", (a.py(0) + a.py(a.y_max)) / 2);
  return s;
}

std::string series(const Axes& a, const ScalingReport& r, std::size_t k) {
  std::string points, marks;
  for (const ScalingRow& row : r.rows) {
    if (row.scheduler != r.schedulers[k]) continue;
    points += fmt::format("{:.1f},{:.1f} ", a.px(row.threads), a.py(row.speedup));
    marks += fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"3.5\" fill=\"{}\"/>\n", a.px(row.threads),
                         a.py(row.speedup), kColours[k % 6]);
  }
  return fmt::format("<polyline points=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"2\"/>\n", points,
                     kColours[k % 6]) + marks;
}

std::string legend(const ScalingReport& r) {
  std::string s;
  const double x = kWidth - kRight + 20;
  double y = kTop + 10;
  for (std::size_t k = 0; k < r.schedulers.size(); ++k, y += 22) {
    s += line(x, y, x + 24, y, fmt::format("stroke=\"{}\" stroke-width=\"2\"", kColours[k % 6]));
    s += text(x + 32, y + 4, r.schedulers[k], "start");
  }
  s += line(x, y, x + 24, y, "stroke=\"#888\" stroke-dasharray=\"5 4\"");
  return s + text(x + 32, y + 4, "ideal", "start");
}

}  // namespace

std::string scaling_svg(const ScalingReport& r) {
  double top = r.threads_max;
  for (const ScalingRow& row : r.rows) top = std::max(top, row.speedup);
  const Axes a{1.0, std::max(2.0, static_cast<double>(r.threads_max)), std::ceil(top * 1.1)};
  std::string s = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} {1}\" "
      "font-family=\"sans-serif\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n", kWidth, kHeight);
  s += text(kLeft, 24,
            fmt::format("{}: speedup against threads ({}x{}, {} spp, {} cores)", xml_escape(r.scene), r.width,
                        r.height, r.spp, r.cores),
            "start", 15);
  s += grid_and_ticks(a);
  s += line(a.px(1), a.py(1), a.px(a.x_max), a.py(a.x_max), "stroke=\"#888\" stroke-dasharray=\"5 4\"");
  if (r.cores >= 1 && r.cores < a.x_max) {
    s += line(a.px(r.cores), a.py(0), a.px(r.cores), a.py(a.y_max), "stroke=\"#aaa\" stroke-dasharray=\"2 3\"");
    s += text(a.px(r.cores) + 4, a.py(a.y_max) + 14, fmt::format("{} cores", r.cores), "start", 11);
  }
  for (std::size_t k = 0; k < r.schedulers.size(); ++k) s += series(a, r, k);
  return s + legend(r) + "</svg>\n";
}

}  // namespace tessera
