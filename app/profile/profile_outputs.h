// The load-balancing outputs of tessera render: --stats-json, --trace and --heatmap.
#pragma once

#include <string>

#include "app/profile/heatmap.h"
#include "renderer/render/render.h"

namespace tessera {

struct ProfileOutputs {
  std::string stats_json, trace, heatmap;  // empty: not wanted
  HeatmapBy heatmap_by = HeatmapBy::cost;
  bool needs_tile_records() const { return !stats_json.empty() || !trace.empty(); }
};

// Throws OutputError for a path that cannot be written; call it before rendering.
void check_profile_outputs(const ProfileOutputs& outputs);

// Writes each requested file atomically; `title` heads the heat map.
void write_profile_outputs(const ProfileOutputs& outputs, const RenderResult& result, const std::string& title);

}  // namespace tessera
