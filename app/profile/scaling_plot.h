// The speedup plot of tessera scaling: speedup against threads (of all ranks, with
// --ranks-max), one line with markers per scheduler (and rank count), the ideal line, a
// dotted mark at the core count, axes with ticks and a legend.
// Drawn with Cairo (app/profile/chart.h): SVG, or PNG and the other raster formats.
#pragma once

#include <string>
#include <vector>

#include "app/profile/chart.h"
#include "app/profile/scaling_report.h"

namespace tessera {

struct PlotSeries {
  std::string name;  // in the legend
  Colour colour;
  std::vector<Point> points;  // (threads of all ranks, speedup)
  bool dashed = false;
  bool markers = true;
};

// What the plot shows, before any drawing: the data its tests check.
struct ScalingPlot {
  std::string title, x_label, y_label;
  double x_min = 1.0, x_max = 2.0, y_max = 1.0;
  std::vector<double> x_ticks, y_ticks;
  std::vector<PlotSeries> series;  // one per rank count and scheduler, in order, then "ideal"
  int cores = 0;  // marked when inside the plot
};

ScalingPlot scaling_plot(const ScalingReport& report);

// Draws and writes the plot atomically. Throws OutputError.
void write_scaling_plot(const std::string& path, const ScalingReport& report);

}  // namespace tessera
