#include "app/profile/profile_outputs.h"

#include "app/profile/chart.h"
#include "imageio/file_output.h"
#include "app/profile/profile_json.h"

namespace tessera {

void check_profile_outputs(const ProfileOutputs& o) {
  if (!o.stats_json.empty()) check_writable_path(o.stats_json);
  if (!o.trace.empty()) check_writable_path(o.trace);
  if (!o.heatmap.empty()) check_chart_path(o.heatmap);
}

void write_profile_outputs(const ProfileOutputs& o, const RenderResult& result, const std::string& title) {
  if (!o.stats_json.empty()) write_stats_json(o.stats_json, result.profile, result.stats);
  if (!o.trace.empty()) write_trace_json(o.trace, result.profile);
  if (!o.heatmap.empty()) write_heatmap(o.heatmap, result.profile, {title, o.heatmap_by});
}

}  // namespace tessera
