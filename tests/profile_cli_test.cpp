// The load-balancing outputs from the command line: render --stats-json --trace --heatmap
// --aov cost, the summary line, and tessera scaling's table, CSV and plot.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <OpenImageIO/imageio.h>
#include <nlohmann/json.hpp>

#include "tests/test_support.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string cornell() { return test::scene_path("cornell-box/cornell-box.gltf"); }

TEST(ProfileCli, RenderWritesStatsTraceHeatmapAndCostLayer) {
  const std::string dir = test::make_temp_dir("profile-cli");
  const test::CommandResult r = test::run_command(
      test::tessera_exe() + " render " + cornell() + " --width 40 --spp 2 --threads 2 --tile-size 16 " +
      "--scheduler counter --tile-order spiral --aov cost -o " + dir + "/f.exr --stats-json " + dir + "/s.json " +
      "--trace " + dir + "/t.json --heatmap " + dir + "/h.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("counter spiral: efficiency"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("imbalance"), std::string::npos);

  const nlohmann::json stats = nlohmann::json::parse(slurp(dir + "/s.json"));
  EXPECT_EQ(stats["scheduler"], "counter");
  EXPECT_EQ(stats["tiles"].size(), 9u);  // 40x40 in tiles of 16
  EXPECT_EQ(stats["tile_runs"].size(), 2u * 9u);  // waves of 1 and 1 sample
  const nlohmann::json trace = nlohmann::json::parse(slurp(dir + "/t.json"));
  std::size_t slices = 0;
  for (const auto& e : trace["traceEvents"]) slices += e["ph"] == "X";
  EXPECT_EQ(slices, 18u);

  auto heatmap = OIIO::ImageInput::open(dir + "/h.png");
  ASSERT_TRUE(heatmap);
  EXPECT_GT(heatmap->spec().width, 40);  // the map is enlarged and has a legend
  EXPECT_EQ(heatmap->spec().nchannels, 3);
  auto exr = OIIO::ImageInput::open(dir + "/f.exr");
  ASSERT_TRUE(exr);
  const auto& names = exr->spec().channelnames;
  EXPECT_NE(std::find(names.begin(), names.end(), "cost.time"), names.end());
  for (const auto& entry : fs::directory_iterator(dir))  // every file was renamed into place
    EXPECT_EQ(entry.path().filename().string().rfind(".tessera-tmp", 0), std::string::npos);
}

TEST(ProfileCli, UnwritableStatsPathFailsBeforeRendering) {
  const test::CommandResult r = test::run_command(test::tessera_exe() + " render " + cornell() +
                                                  " --width 16 --spp 1 -o /tmp/x.exr --stats-json /nonexistent/s.json");
  EXPECT_EQ(r.exit_code, 2);  // a bad output path is bad usage
  EXPECT_NE(r.err.find("/nonexistent/s.json"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("M samples/s"), std::string::npos) << "rendered anyway";
}

TEST(ProfileCli, UnknownSchedulerIsABadUsage) {
  const test::CommandResult r =
      test::run_command(test::tessera_exe() + " render " + cornell() + " --scheduler guided -o /tmp/x.exr");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--scheduler"), std::string::npos) << r.err;
}

TEST(ProfileCli, ScalingWritesTableCsvAndPlot) {
  const std::string dir = test::make_temp_dir("scaling-cli") + "/out";
  const test::CommandResult r =
      test::run_command(test::tessera_exe() + " scaling " + cornell() +
                        " --threads-max 3 --schedulers tiles,chunks --spp 1 --width 24 --repeat 1 --out " + dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream csv(slurp(dir + "/scaling.csv"));
  std::string line;
  int rows = 0;
  std::getline(csv, line);
  EXPECT_EQ(line.rfind("scene,scheduler,threads,wall_seconds_median", 0), 0u);
  while (std::getline(csv, line)) ++rows;
  EXPECT_EQ(rows, 2 * 3);  // two schedulers, 1..3 threads
  const std::string md = slurp(dir + "/scaling.md");
  EXPECT_NE(md.find("| chunks | 3 |"), std::string::npos) << md;
  const std::string svg = slurp(dir + "/scaling.svg");  // what it shows: charts_test.cpp
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
}

TEST(ProfileCli, HeatmapAsSvg) {
  const std::string dir = test::make_temp_dir("heatmap-svg");
  const test::CommandResult r = test::run_command(test::tessera_exe() + " render " + cornell() +
                                                  " --width 24 --spp 1 -o " + dir + "/f.exr --heatmap " + dir +
                                                  "/h.svg");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string svg = slurp(dir + "/h.svg");
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
}

TEST(ProfileCli, HeatmapInAnUnknownFormatFailsBeforeRendering) {
  const test::CommandResult r = test::run_command(test::tessera_exe() + " render " + cornell() +
                                                  " --width 16 --spp 1 -o /tmp/x.exr --heatmap /tmp/h.nosuchformat");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("/tmp/h.nosuchformat"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("M samples/s"), std::string::npos) << "rendered anyway";
}

}  // namespace
}  // namespace tessera
