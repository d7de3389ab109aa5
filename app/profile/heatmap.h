// --heatmap: the CPU time spent on each tile (summed over the sample waves) as a colour map
// over the image, with pixel axes, a colour bar with its unit, and a one-line summary of the
// frame. CPU time, not wall time, so a busy machine's preemptions do not show up as expensive
// tiles. Drawn with Cairo (app/profile/chart.h): PNG or any 8-bit format OpenImageIO writes, or SVG.
// By rank instead (a distributed render): each tile in the colour of the MPI rank that spent
// the most CPU time on it.
#pragma once

#include <string>
#include <vector>

#include "app/profile/chart.h"
#include "renderer/profile/render_stats.h"

namespace tessera {

enum class HeatmapBy { cost, rank };

struct HeatmapParams {
  std::string title;  // drawn above the map, e.g. the scene and scheduler
  HeatmapBy by = HeatmapBy::cost;
};

struct LegendEntry {
  std::string label;
  Colour colour;
};

struct HeatmapCell {
  Tile rect;  // in frame pixels
  double cpu_seconds = 0.0;
  Colour colour;  // viridis of cpu_seconds / the dearest tile's; by rank, the rank's
  int rank = 0;  // the rank that spent the most CPU time on it
};

// What the heat map shows, before any drawing: the data its tests check.
struct HeatmapPlot {
  std::string title, summary;
  int width = 0, height = 0;  // the frame in pixels
  std::vector<HeatmapCell> cells;
  std::string unit;  // the colour bar's: "ms" below a second, else "s"
  double bar_max = 0.0;  // the top of the colour bar in `unit`: the dearest tile
  std::vector<double> bar_ticks;  // labelled values on the colour bar, in `unit`
  std::string bar_label;  // beside the colour bar
  // By rank with at most kCategoryColours ranks: a swatch per rank instead of the bar (more
  // ranks: viridis over the rank number, with a bar).
  std::vector<LegendEntry> legend;
};

HeatmapPlot heatmap_plot(const FrameProfile& profile, const HeatmapParams& params);

// Draws and writes the heat map atomically. Throws OutputError.
void write_heatmap(const std::string& path, const FrameProfile& profile, const HeatmapParams& params);

}  // namespace tessera
