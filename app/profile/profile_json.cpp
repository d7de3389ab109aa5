#include "app/profile/profile_json.h"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "imageio/file_output.h"

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
          {"cancelled", stats.cancelled},
          {"ranks", std::max<std::size_t>(1, p.ranks.size())}};
}

// The ranks of a distributed render; one process is rank 0 with no communication.
std::vector<RankStats> ranks_of(const FrameProfile& p) {
  if (!p.ranks.empty()) return p.ranks;
  RankStats one;
  one.threads = static_cast<int>(p.threads.size());
  for (const ThreadStats& t : p.threads) one.busy += t.busy, one.cpu += t.cpu, one.items += t.items;
  one.idle = one.threads * p.balance.wall - one.busy;
  one.efficiency = p.balance.efficiency;
  return {one};
}

json ranks_json(const FrameProfile& p) {
  json out = json::array();
  for (const RankStats& r : ranks_of(p))
    out.push_back({{"rank", r.rank}, {"threads", r.threads}, {"busy_seconds", r.busy}, {"idle_seconds", r.idle},
                   {"communication_seconds", r.communication}, {"cpu_seconds", r.cpu}, {"items", r.items},
                   {"efficiency", r.efficiency}});
  return out;
}

json threads_json(const FrameProfile& p) {
  json out = json::array();
  for (std::size_t t = 0; t < p.threads.size(); ++t) {
    const ThreadStats& s = p.threads[t];
    out.push_back({{"rank", s.rank}, {"thread", s.thread}, {"busy_seconds", s.busy}, {"idle_seconds", s.idle}, {"cpu_seconds", s.cpu},
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
  for (std::size_t t = 0; t < p.plan.tiles.size(); ++t) {
    out.push_back({{"tile", t},
                   {"column", t % p.plan.grid.columns},
                   {"row", t / p.plan.grid.columns},
                   {"rect", rect_json(p.plan.tiles[t])},
                   {"seconds", seconds[t]},
                   {"cpu_seconds", cpu[t]}});
    if (!p.tile_rank.empty()) out.back()["rank"] = p.tile_rank[t];  // the rank that spent the most on it
  }
  return out;
}

json runs_json(const FrameProfile& p) {
  json out = json::array();
  for (const TileRecord& r : p.records) {
    if (r.thread < 0) continue;
    const WorkItem& item = p.plan.items[r.item];
    out.push_back({{"tile", item.tile}, {"rect", rect_json(item.rect)}, {"wave", r.wave}, {"rank", r.rank}, {"thread", r.thread},
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

// One trace process per rank: pid rank + 1.
json metadata_event(const char* name, int rank, int tid, json args) {
  return {{"name", name}, {"ph", "M"}, {"pid", rank + 1}, {"tid", tid}, {"args", std::move(args)}};
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
          {"per_rank", ranks_json(p)},
          {"per_thread", threads_json(p)},
          {"waves", waves_json(p)},
          {"tiles", tiles_json(p)},
          {"tile_runs", runs_json(p)}};
}

json trace_json(const FrameProfile& p) {
  const WorkPlanParams& pp = p.plan.params;
  json events = json::array();
  const bool distributed = !p.ranks.empty();
  for (const RankStats& rank : ranks_of(p)) {
    const int r = rank.rank;
    const std::string name = distributed ? "rank " + std::to_string(r)
                                         : std::string("tessera ") + scheduler_name(pp.scheduler) + ", " +
                                               tile_order_name(pp.order) + ", " + std::to_string(pp.threads) + " threads";
    events.push_back(metadata_event("process_name", r, 0, {{"name", name}}));
    events.push_back(metadata_event("process_sort_index", r, 0, {{"sort_index", r}}));
    for (int t = 0; t < rank.threads; ++t) {
      events.push_back(metadata_event("thread_name", r, t, {{"name", "thread " + std::to_string(t)}}));
      events.push_back(metadata_event("thread_sort_index", r, t, {{"sort_index", t}}));
    }
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
                      {"pid", r.rank + 1},
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
