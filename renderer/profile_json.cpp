#include "renderer/profile_json.h"

#include <cmath>

#include <nlohmann/json.hpp>

#include "renderer/file_output.h"

namespace tessera {

using nlohmann::json;

namespace {

// Trace times are microseconds; nanosecond resolution is all a steady clock gives.
double micros(double seconds) { return std::round(seconds * 1e9) / 1e3; }

json rect_json(const Tile& r) { return json::array({r.x0, r.y0, r.x1, r.y1}); }

json frame_json(const FrameProfile& p, const RenderStats& stats) {
  const LoadBalance& b = p.balance;
  return {{"wall_seconds", b.wall},
          {"parallel_efficiency", b.efficiency},
          {"imbalance", b.imbalance},
          {"tail_seconds", b.tail},
          {"cpu_share", b.cpu_share},
          {"render_seconds", stats.seconds},
          {"camera_samples", stats.camera_samples},
          {"rays", stats.rays},
          {"cancelled", stats.cancelled}};
}

json threads_json(const FrameProfile& p) {
  json out = json::array();
  for (std::size_t t = 0; t < p.threads.size(); ++t) {
    const ThreadStats& s = p.threads[t];
    out.push_back({{"thread", t}, {"busy_seconds", s.busy}, {"idle_seconds", s.idle}, {"cpu_seconds", s.cpu},
                   {"items", s.items}});
  }
  return out;
}

json waves_json(const FrameProfile& p) {
  json out = json::array();
  for (std::size_t w = 0; w < p.waves.size(); ++w) {
    const WaveStats& s = p.waves[w];
    out.push_back({{"wave", w}, {"samples", {s.sample_begin, s.sample_end}}, {"start", s.start}, {"end", s.end},
                   {"tail_seconds", s.tail}});
  }
  return out;
}

json tiles_json(const FrameProfile& p) {
  const std::vector<double> seconds = tile_seconds(p), cpu = tile_seconds(p, TileClock::cpu);
  json out = json::array();
  for (std::size_t t = 0; t < p.plan.tiles.size(); ++t)
    out.push_back({{"tile", t},
                   {"column", t % p.plan.grid.columns},
                   {"row", t / p.plan.grid.columns},
                   {"rect", rect_json(p.plan.tiles[t])},
                   {"seconds", seconds[t]},
                   {"cpu_seconds", cpu[t]}});
  return out;
}

json runs_json(const FrameProfile& p) {
  json out = json::array();
  for (const TileRecord& r : p.records) {
    if (r.thread < 0) continue;
    const WorkItem& item = p.plan.items[r.item];
    out.push_back({{"tile", item.tile}, {"rect", rect_json(item.rect)}, {"wave", r.wave}, {"thread", r.thread},
                   {"start", r.start}, {"end", r.end}, {"cpu_seconds", r.cpu}, {"samples", r.samples},
                   {"rays", r.rays}});
  }
  return out;
}

std::string tile_name(const FrameProfile& p, const TileRecord& r) {
  const WorkItem& item = p.plan.items[r.item];
  const int c = item.tile % p.plan.grid.columns, row = item.tile / p.plan.grid.columns;
  return "tile " + std::to_string(c) + "," + std::to_string(row) + " wave " + std::to_string(r.wave);
}

json metadata_event(const char* name, int tid, json args) {
  return {{"name", name}, {"ph", "M"}, {"pid", 1}, {"tid", tid}, {"args", std::move(args)}};
}

}  // namespace

json stats_json(const FrameProfile& p, const RenderStats& stats) {
  const WorkPlanParams& pp = p.plan.params;
  return {{"schema_version", kStatsSchemaVersion},
          {"scheduler", scheduler_name(pp.scheduler)},
          {"tile_order", tile_order_name(pp.order)},
          {"threads", pp.threads},
          {"width", pp.width},
          {"height", pp.height},
          {"tile_size", pp.tile_size},
          {"spp", p.waves.empty() ? 0 : p.waves.back().sample_end},
          {"frame", frame_json(p, stats)},
          {"per_thread", threads_json(p)},
          {"waves", waves_json(p)},
          {"tiles", tiles_json(p)},
          {"tile_runs", runs_json(p)}};
}

json trace_json(const FrameProfile& p) {
  const WorkPlanParams& pp = p.plan.params;
  json events = json::array();
  events.push_back(metadata_event("process_name", 0,
                                  {{"name", std::string("tessera ") + scheduler_name(pp.scheduler) + ", " +
                                                tile_order_name(pp.order) + ", " + std::to_string(pp.threads) +
                                                " threads"}}));
  for (int t = 0; t < pp.threads; ++t) {
    events.push_back(metadata_event("thread_name", t, {{"name", "thread " + std::to_string(t)}}));
    events.push_back(metadata_event("thread_sort_index", t, {{"sort_index", t}}));
  }
  for (std::size_t w = 0; w < p.waves.size(); ++w)  // wave boundaries as global markers
    events.push_back({{"name", "wave " + std::to_string(w)}, {"ph", "i"}, {"s", "g"}, {"pid", 1}, {"tid", 0},
                      {"ts", micros(p.waves[w].start)}});
  for (const TileRecord& r : p.records) {
    if (r.thread < 0) continue;
    const WorkItem& item = p.plan.items[r.item];
    events.push_back({{"name", tile_name(p, r)},
                      {"cat", "tile"},
                      {"ph", "X"},
                      {"pid", 1},
                      {"tid", r.thread},
                      {"ts", micros(r.start)},
                      {"dur", micros(r.end - r.start)},
                      {"args", {{"rect", rect_json(item.rect)}, {"cpu_us", micros(r.cpu)}, {"samples", r.samples},
                                {"rays", r.rays}}}});
  }
  return {{"traceEvents", std::move(events)},
          {"displayTimeUnit", "ms"},
          {"otherData", {{"scheduler", scheduler_name(pp.scheduler)}, {"tile_order", tile_order_name(pp.order)},
                         {"parallel_efficiency", p.balance.efficiency}, {"imbalance", p.balance.imbalance}}}};
}

void write_stats_json(const std::string& path, const FrameProfile& profile, const RenderStats& stats) {
  write_text_file(path, stats_json(profile, stats).dump(1) + "\n");
}

void write_trace_json(const std::string& path, const FrameProfile& profile) {
  write_text_file(path, trace_json(profile).dump() + "\n");
}

}  // namespace tessera
