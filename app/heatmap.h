// --heatmap: the CPU time spent on each tile (summed over the sample waves) as a colour map
// over the image, with a colour bar, its scale and a one-line summary of the frame. CPU
// time, not wall time, so a busy machine's preemptions do not show up as expensive tiles.
#pragma once

#include <string>

#include "app/canvas.h"
#include "renderer/render_stats.h"

namespace tessera {

struct HeatmapParams {
  std::string title;  // drawn above the map, e.g. the scene and scheduler
};

Canvas draw_heatmap(const FrameProfile& profile, const HeatmapParams& params);

// PNG or any 8-bit format OpenImageIO writes, atomically. Throws OutputError.
void write_heatmap(const std::string& path, const FrameProfile& profile, const HeatmapParams& params);

}  // namespace tessera
