// The charts tessera draws with Cairo (app/profile/chart.h): what the heat map and the scaling plot
// show (cell colours from known tile costs, the colour bar's range and unit, the plotted
// points and legend), the viridis colours from OpenImageIO, ticks, and the files written.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include <OpenImageIO/imageio.h>

#include "app/profile/colormap.h"
#include "app/profile/heatmap.h"
#include "app/profile/scaling_plot.h"
#include "imageio/image_output.h"
#include "tests/test_support.h"

namespace tessera {
namespace {

void expect_colour(Colour got, Colour want, const char* what) {
  EXPECT_NEAR(got.r, want.r, 0.01) << what;
  EXPECT_NEAR(got.g, want.g, 0.01) << what;
  EXPECT_NEAR(got.b, want.b, 0.01) << what;
}

// matplotlib's viridis table at 0, 0.25, 0.5 and 1.
const Colour kViridis0{0.267, 0.005, 0.329}, kViridisQuarter{0.229, 0.322, 0.546},
    kViridisHalf{0.128, 0.567, 0.551}, kViridis1{0.993, 0.906, 0.144};

TEST(Colormap, ViridisIsMatplotlibsInSrgb) {
  const std::vector<Colour> c = viridis({0.0, 0.25, 0.5, 1.0, -3.0, 7.0});
  ASSERT_EQ(c.size(), 6u);
  expect_colour(c[0], kViridis0, "0");
  expect_colour(c[1], kViridisQuarter, "0.25");
  expect_colour(c[2], kViridisHalf, "0.5");
  expect_colour(c[3], kViridis1, "1");
  expect_colour(c[4], kViridis0, "clamped below");
  expect_colour(c[5], kViridis1, "clamped above");
  const std::vector<Colour> ramp = viridis_ramp(3);
  expect_colour(ramp[1], kViridisHalf, "ramp middle");
}

TEST(Chart, TicksAreRoundNumbers) {
  EXPECT_DOUBLE_EQ(tick_step(69.3, 5), 20.0);
  EXPECT_DOUBLE_EQ(tick_step(40.0, 5), 10.0);
  EXPECT_DOUBLE_EQ(tick_step(0.35, 5), 0.1);
  EXPECT_DOUBLE_EQ(tick_step(200.0, 6), 50.0);
  EXPECT_EQ(ticks(0.0, 69.3, 20.0), (std::vector<double>{0, 20, 40, 60}));
  EXPECT_EQ(ticks(1.0, 4.0, 1.0), (std::vector<double>{1, 2, 3, 4}));
  EXPECT_FALSE(std::signbit(ticks(0.0, 1.0, 0.5)[0]));  // "0", never "-0"
}

// A 64x32 frame of two 32-pixel tiles whose CPU times are known.
FrameProfile two_tiles(double left_seconds, double right_seconds) {
  FrameProfile p;
  p.plan = make_work_plan({64, 32, 32, 1});
  p.item_cpu_seconds.assign(p.plan.items.size(), 0.0);
  p.item_seconds.assign(p.plan.items.size(), 0.0);
  for (std::size_t i = 0; i < p.plan.items.size(); ++i)
    p.item_cpu_seconds[i] = p.plan.items[i].tile == 0 ? left_seconds : right_seconds;
  p.balance.efficiency = 0.9;
  p.balance.imbalance = 1.25;
  return p;
}

TEST(Heatmap, CellColoursFollowTheirCost) {
  const HeatmapPlot p = heatmap_plot(two_tiles(0.010, 0.040), {"two tiles"});
  EXPECT_EQ(p.title, "two tiles");
  EXPECT_EQ(p.width, 64);
  EXPECT_EQ(p.height, 32);
  ASSERT_EQ(p.cells.size(), 2u);
  EXPECT_EQ(p.cells[1].rect.x0, 32);
  EXPECT_DOUBLE_EQ(p.cells[0].cpu_seconds, 0.010);
  expect_colour(p.cells[0].colour, kViridisQuarter, "a quarter of the dearest");
  expect_colour(p.cells[1].colour, kViridis1, "the dearest tile");
  EXPECT_EQ(p.summary, "tile CPU time: max 0.04 s, mean 0.025 s; efficiency 90.0%, imbalance 1.25");
}

TEST(Heatmap, ColourBarSpansZeroToTheDearestTileInItsUnit) {
  const HeatmapPlot ms = heatmap_plot(two_tiles(0.010, 0.040), {});
  EXPECT_EQ(ms.unit, "ms");
  EXPECT_DOUBLE_EQ(ms.bar_max, 40.0);
  EXPECT_EQ(ms.bar_ticks, (std::vector<double>{0, 10, 20, 30, 40}));
  const HeatmapPlot s = heatmap_plot(two_tiles(1.5, 3.0), {});
  EXPECT_EQ(s.unit, "s");
  EXPECT_DOUBLE_EQ(s.bar_max, 3.0);
  EXPECT_EQ(s.bar_ticks, (std::vector<double>{0, 1, 2, 3}));
  const HeatmapPlot idle = heatmap_plot(two_tiles(0.0, 0.0), {});
  EXPECT_TRUE(idle.bar_ticks.empty());
  expect_colour(idle.cells[1].colour, kViridis0, "no cost anywhere");
}

// Two ranks, each the busiest on one tile: each tile in its rank's colour, a legend of ranks.
TEST(Heatmap, ByRankColoursEachTileAsTheRankThatSpentMostOnIt) {
  FrameProfile p = two_tiles(0.010, 0.040);
  p.ranks.resize(2);
  p.tile_rank = {1, 0};
  const HeatmapPlot h = heatmap_plot(p, {"ranks", HeatmapBy::rank});
  ASSERT_EQ(h.cells.size(), 2u);
  EXPECT_EQ(h.cells[0].rank, 1);
  expect_colour(h.cells[0].colour, hex_colour(0xD55E00), "rank 1: Okabe-Ito vermillion");
  expect_colour(h.cells[1].colour, hex_colour(0x0072B2), "rank 0: Okabe-Ito blue");
  ASSERT_EQ(h.legend.size(), 2u);
  EXPECT_EQ(h.legend[1].label, "rank 1");
  EXPECT_TRUE(h.bar_ticks.empty());
  EXPECT_EQ(h.summary, "tile colour: the rank that spent the most CPU time on it; 2 ranks, cluster efficiency 90.0%");
  // More ranks than category colours: viridis over the rank number, with a bar.
  p.ranks.resize(9);
  p.tile_rank = {8, 0};
  const HeatmapPlot many = heatmap_plot(p, {"ranks", HeatmapBy::rank});
  EXPECT_TRUE(many.legend.empty());
  expect_colour(many.cells[0].colour, kViridis1, "the last rank");
  expect_colour(many.cells[1].colour, kViridis0, "rank 0");
  EXPECT_EQ(many.bar_label, "rank");
  EXPECT_DOUBLE_EQ(many.bar_max, 8.0);
}

TEST(Heatmap, WritesPngAndSvg) {
  const std::string dir = test::make_temp_dir("heatmap");
  const FrameProfile profile = two_tiles(0.010, 0.040);
  write_heatmap(dir + "/h.png", profile, {"png"});
  auto png = OIIO::ImageInput::open(dir + "/h.png");
  ASSERT_TRUE(png);
  EXPECT_GT(png->spec().width, 64 * 8);  // a small frame is enlarged 8 times, plus its legend
  EXPECT_EQ(png->spec().nchannels, 3);
  write_heatmap(dir + "/h.SVG", profile, {"svg"});
  std::ifstream in(dir + "/h.SVG");
  std::stringstream svg;
  svg << in.rdbuf();
  EXPECT_NE(svg.str().find("<svg"), std::string::npos);
  EXPECT_THROW(check_chart_path(dir + "/h.nosuchformat"), OutputPathError);
  EXPECT_NO_THROW(check_chart_path(dir + "/h.svg"));
}

ScalingReport two_schedulers() {
  ScalingReport r;
  r.scene = "box.gltf";
  r.width = 64;
  r.height = 48;
  r.spp = 2;
  r.cores = 2;
  r.threads_max = 3;
  r.schedulers = {"tiles", "chunks"};
  const double speedups[2][3] = {{1.0, 1.9, 2.4}, {1.0, 1.5, 3.4}};
  for (int s = 0; s < 2; ++s)
    for (int n = 1; n <= 3; ++n) {
      ScalingRow row;
      row.scheduler = r.schedulers[s];
      row.threads = n;
      row.speedup = speedups[s][n - 1];
      r.rows.push_back(row);
    }
  return r;
}

TEST(ScalingPlot, PlotsEachSchedulersSpeedupsAndTheIdealLine) {
  const ScalingPlot p = scaling_plot(two_schedulers());
  EXPECT_EQ(p.title, "box.gltf: speedup against threads (64x48, 2 spp, 2 cores)");
  EXPECT_EQ(p.x_label, "threads");
  ASSERT_EQ(p.series.size(), 3u);
  EXPECT_EQ(p.series[0].name, "tiles");
  EXPECT_EQ(p.series[1].name, "chunks");
  EXPECT_EQ(p.series[2].name, "ideal");
  EXPECT_TRUE(p.series[2].dashed);
  EXPECT_EQ(p.series[1].points, (std::vector<Point>{{1, 1.0}, {2, 1.5}, {3, 3.4}}));
  EXPECT_EQ(p.series[2].points, (std::vector<Point>{{1, 1}, {3, 3}}));
  EXPECT_DOUBLE_EQ(p.x_max, 3.0);
  EXPECT_DOUBLE_EQ(p.y_max, 4.0);  // 3.4 and a tenth of headroom, rounded up
  EXPECT_EQ(p.x_ticks, (std::vector<double>{1, 2, 3}));
  EXPECT_EQ(p.y_ticks, (std::vector<double>{0, 1, 2, 3, 4}));
  EXPECT_EQ(p.cores, 2);
}

// Ranks x threads: a series per scheduler and rank count, against the threads of all ranks.
TEST(ScalingPlot, PlotsRankCountsAgainstTheThreadsOfAllRanks) {
  ScalingReport r = two_schedulers();
  r.schedulers = {"tiles"};
  r.rows.resize(3);  // tiles at 1, 2 and 3 threads
  r.ranks_max = 2;
  for (int n = 1; n <= 3; ++n) {
    ScalingRow row;
    row.scheduler = "tiles";
    row.ranks = 2;
    row.threads = n;
    row.speedup = 1.5 * n;
    r.rows.push_back(row);
  }
  const ScalingPlot p = scaling_plot(r);
  EXPECT_EQ(p.title, "box.gltf: speedup against ranks x threads (64x48, 2 spp, 2 cores)");
  ASSERT_EQ(p.series.size(), 3u);
  EXPECT_EQ(p.series[0].name, "tiles");
  EXPECT_EQ(p.series[1].name, "tiles, 2 ranks");
  EXPECT_EQ(p.series[1].points, (std::vector<Point>{{2, 1.5}, {4, 3.0}, {6, 4.5}}));
  EXPECT_DOUBLE_EQ(p.x_max, 6.0);
  EXPECT_EQ(p.series[2].points, (std::vector<Point>{{1, 1}, {6, 6}}));  // the ideal line
}

TEST(ScalingPlot, WritesSvgOrPng) {
  const std::string dir = test::make_temp_dir("scaling-plot");
  write_scaling_plot(dir + "/s.png", two_schedulers());
  auto png = OIIO::ImageInput::open(dir + "/s.png");
  ASSERT_TRUE(png);
  EXPECT_EQ(png->spec().width, 680);
  EXPECT_EQ(png->spec().height, 440);
}

}  // namespace
}  // namespace tessera
