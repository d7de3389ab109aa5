// The load-balance profile adds up: tile times sum to each thread's busy time, every tile
// runs once per sample wave, the frame figures follow from the threads', and the trace is
// valid trace-event JSON with one slice per tile run.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include <nlohmann/json.hpp>

#include "app/profile/profile_json.h"
#include "tests/schedule_fixture.h"

namespace tessera {
namespace {

RenderResult profiled(SchedulerKind k, int threads = 3) {
  return test::render_schedule_case({k, TileOrder::hilbert, threads, 8, true});
}

TEST(RenderStats, EveryTileRunsOncePerWaveAndItsSamplesAddUp) {
  for (SchedulerKind k : test::all_schedulers()) {
    const RenderResult r = profiled(k);
    const FrameProfile& p = r.profile;
    ASSERT_EQ(p.waves.size(), 3u) << scheduler_name(k);  // 7 spp: waves of 1, 2, 4
    ASSERT_EQ(p.records.size(), 3 * p.plan.items.size());
    std::uint64_t samples = 0, rays = 0;
    for (std::size_t i = 0; i < p.records.size(); ++i) {
      const TileRecord& rec = p.records[i];
      EXPECT_EQ(rec.item, static_cast<int>(i % p.plan.items.size()));
      EXPECT_EQ(rec.wave, static_cast<int>(i / p.plan.items.size()));
      ASSERT_GE(rec.thread, 0) << "never ran";
      ASSERT_LT(rec.thread, 3);
      const WaveStats& w = p.waves[rec.wave];
      EXPECT_EQ(rec.samples, static_cast<std::uint64_t>(p.plan.items[rec.item].rect.pixel_count()) *
                                 (w.sample_end - w.sample_begin));
      EXPECT_LE(w.start, rec.start);
      EXPECT_LE(rec.start, rec.end);
      EXPECT_LE(rec.end, w.end);
      EXPECT_GE(rec.cpu, 0.0);
      EXPECT_LE(rec.cpu, rec.end - rec.start + 1e-4) << "more CPU time than wall time on one thread";
      samples += rec.samples;
      rays += rec.rays;
    }
    EXPECT_EQ(samples, r.stats.camera_samples);
    EXPECT_EQ(samples, 45u * 37u * 7u);
    EXPECT_EQ(rays, r.stats.rays);
  }
}

TEST(RenderStats, TileTimesSumToEachThreadsBusyTimeAndNeverOverlap) {
  for (SchedulerKind k : test::all_schedulers()) {
    const FrameProfile p = profiled(k).profile;
    ASSERT_EQ(p.threads.size(), 3u);
    std::map<int, std::vector<const TileRecord*>> by_thread;
    for (const TileRecord& rec : p.records) by_thread[rec.thread].push_back(&rec);
    for (int t = 0; t < 3; ++t) {
      double busy = 0.0;
      std::vector<const TileRecord*>& runs = by_thread[t];
      std::sort(runs.begin(), runs.end(), [](auto* a, auto* b) { return a->start < b->start; });
      for (std::size_t i = 0; i < runs.size(); ++i) {
        busy += runs[i]->end - runs[i]->start;
        if (i > 0) {
          EXPECT_LE(runs[i - 1]->end, runs[i]->start) << "one thread, two tiles at once";
        }
      }
      EXPECT_NEAR(busy, p.threads[t].busy, 1e-9) << scheduler_name(k) << " thread " << t;
      EXPECT_EQ(runs.size(), p.threads[t].items);
      EXPECT_NEAR(p.threads[t].busy + p.threads[t].idle, p.balance.wall, 1e-9);
    }
  }
}

TEST(RenderStats, FrameFiguresFollowFromTheThreads) {
  const FrameProfile p = profiled(SchedulerKind::counter).profile;
  double busy = 0.0, most = 0.0;
  for (const ThreadStats& t : p.threads) {
    busy += t.busy;
    most = std::max(most, t.busy);
  }
  EXPECT_NEAR(p.balance.wall, p.waves.back().end - p.waves.front().start, 1e-12);
  EXPECT_NEAR(p.balance.efficiency, busy / (3 * p.balance.wall), 1e-12);
  EXPECT_NEAR(p.balance.imbalance, most / (busy / 3), 1e-12);
  EXPECT_GT(p.balance.efficiency, 0.0);
  EXPECT_LE(p.balance.efficiency, 1.0);
  EXPECT_GE(p.balance.imbalance, 1.0);
  double tails = 0.0;
  for (const WaveStats& w : p.waves) {
    EXPECT_GE(w.tail, 0.0);
    EXPECT_LE(w.tail, w.end - w.start);
    tails += w.tail;
  }
  EXPECT_NEAR(p.balance.tail, tails, 1e-12);
  double cpu = 0.0;
  for (const ThreadStats& t : p.threads) cpu += t.cpu;
  EXPECT_NEAR(p.balance.cpu_share, cpu / busy, 1e-12);
  double tile_total = 0.0;
  for (double s : tile_seconds(p)) tile_total += s;
  EXPECT_NEAR(tile_total, busy, 1e-9);
  double tile_cpu = 0.0;
  for (double s : tile_seconds(p, TileClock::cpu)) tile_cpu += s;
  EXPECT_NEAR(tile_cpu, cpu, 1e-9);
}

TEST(RenderStats, StaticSchedulersRunExactlyTheirOwnItems) {
  const FrameProfile chunks = profiled(SchedulerKind::chunks).profile;
  for (const TileRecord& rec : chunks.records) EXPECT_EQ(rec.thread, chunks.plan.items[rec.item].chunk);
  const FrameProfile rr = profiled(SchedulerKind::interleaved).profile;
  for (const TileRecord& rec : rr.records) EXPECT_EQ(rec.thread, rec.item % 3);
}

TEST(RenderStats, OneThreadsTailIsOnlyWhatFollowsItsLastTile) {
  const FrameProfile p = profiled(SchedulerKind::counter, 1).profile;
  EXPECT_DOUBLE_EQ(p.balance.imbalance, 1.0);
  for (std::size_t w = 0; w < p.waves.size(); ++w) {
    double last_end = p.waves[w].start;
    for (const TileRecord& rec : p.records)
      if (rec.wave == static_cast<int>(w)) last_end = std::max(last_end, rec.end);
    EXPECT_NEAR(p.waves[w].tail, p.waves[w].end - last_end, 1e-12);
  }
  EXPECT_GT(p.balance.efficiency, 0.5);  // idle only between tiles (a shared machine may preempt)
}

TEST(RenderStats, WithoutRecordsThereAreNoneButTheBalanceIsStillMeasured) {
  const RenderResult r = test::render_schedule_case({SchedulerKind::tiles, TileOrder::scanline, 2});
  EXPECT_TRUE(r.profile.records.empty());
  EXPECT_GT(r.stats.efficiency, 0.0);
  EXPECT_GE(r.stats.imbalance, 1.0);
  EXPECT_EQ(r.profile.item_seconds.size(), r.profile.plan.items.size());
}

TEST(RenderStats, CostLayerGivesEveryPixelItsTilesCpuTime) {
  const FrameProfile p = profiled(SchedulerKind::chunks).profile;
  const std::vector<float> cost = tile_cost_image(p);
  const std::vector<double> seconds = tile_seconds(p, TileClock::cpu);
  ASSERT_EQ(cost.size(), 45u * 37u);
  for (std::size_t t = 0; t < p.plan.tiles.size(); ++t) {
    const Tile& r = p.plan.tiles[t];
    EXPECT_FLOAT_EQ(cost[r.y0 * 45 + r.x0], static_cast<float>(seconds[t]));
    EXPECT_FLOAT_EQ(cost[(r.y1 - 1) * 45 + r.x1 - 1], static_cast<float>(seconds[t]));
  }
}

TEST(TraceJson, IsTraceEventJsonWithOneSlicePerTileRun) {
  const FrameProfile p = profiled(SchedulerKind::tiles).profile;
  const nlohmann::json trace = nlohmann::json::parse(trace_json(p).dump());  // survives a round trip
  ASSERT_TRUE(trace.contains("traceEvents"));
  ASSERT_TRUE(trace["traceEvents"].is_array());
  std::size_t slices = 0;
  std::map<int, bool> named;
  std::map<std::string, int> names;
  for (const nlohmann::json& e : trace["traceEvents"]) {
    ASSERT_TRUE(e["ph"].is_string());
    ASSERT_TRUE(e["pid"].is_number_integer());
    ASSERT_TRUE(e["tid"].is_number_integer());
    const std::string ph = e["ph"];
    if (ph == "M" && e["name"] == "thread_name") named[e["tid"].get<int>()] = true;
    if (ph != "X") continue;
    ++slices;
    ASSERT_TRUE(e["name"].is_string());
    ASSERT_TRUE(e["ts"].is_number());
    ASSERT_TRUE(e["dur"].is_number());
    EXPECT_GE(e["dur"].get<double>(), 0.0);
    EXPECT_GE(e["tid"].get<int>(), 0);
    EXPECT_LT(e["tid"].get<int>(), 3);
    ++names[e["name"].get<std::string>()];
  }
  EXPECT_EQ(slices, p.records.size());
  EXPECT_EQ(names.size(), slices) << "each slice names its tile and wave";
  EXPECT_EQ(names.count("tile 0,0 wave 0"), 1u);
  EXPECT_EQ(named.size(), 3u) << "one named track per thread";
}

TEST(StatsJson, HoldsTheFrameThreadsWavesTilesAndRuns) {
  const RenderResult r = profiled(SchedulerKind::interleaved);
  const nlohmann::json s = nlohmann::json::parse(stats_json(r.profile, r.stats).dump());
  EXPECT_EQ(s["scheduler"], "interleaved");
  EXPECT_EQ(s["tile_order"], "hilbert");
  EXPECT_EQ(s["threads"], 3);
  EXPECT_EQ(s["spp"], 7);
  EXPECT_NEAR(s["frame"]["parallel_efficiency"].get<double>(), r.profile.balance.efficiency, 1e-12);
  EXPECT_NEAR(s["frame"]["imbalance"].get<double>(), r.profile.balance.imbalance, 1e-12);
  EXPECT_TRUE(s["frame"]["tail_seconds"].is_number());
  EXPECT_EQ(s["per_thread"].size(), 3u);
  EXPECT_EQ(s["waves"].size(), 3u);
  EXPECT_EQ(s["tiles"].size(), r.profile.plan.tiles.size());
  EXPECT_EQ(s["tile_runs"].size(), r.profile.records.size());
  for (const char* key : {"tile", "rect", "wave", "thread", "start", "end", "samples", "rays"})
    EXPECT_TRUE(s["tile_runs"][0].contains(key)) << key;
}

TEST(StatsJson, NamesItsSchemaVersion) {
  const RenderResult r = profiled(SchedulerKind::tiles);
  const nlohmann::json s = stats_json(r.profile, r.stats);
  EXPECT_EQ(s["schema_version"], 1);  // docs/load-balancing.md describes version 1
  EXPECT_EQ(kStatsSchemaVersion, 1);
}

}  // namespace
}  // namespace tessera
