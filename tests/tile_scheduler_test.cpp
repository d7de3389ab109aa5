#include <gtest/gtest.h>

#include <atomic>
#include <vector>

#include "renderer/parallel/tile_scheduler.h"

namespace tessera {
namespace {

TEST(TileScheduler, TilesCoverEveryPixelExactlyOnce) {
  for (int size : {1, 7, 32, 500}) {
    const int w = 101, h = 37;
    std::vector<int> covered(w * h, 0);
    for (const Tile& t : make_tiles(w, h, size)) {
      EXPECT_LE(t.x1 - t.x0, size);
      EXPECT_LE(t.y1 - t.y0, size);
      for (int y = t.y0; y < t.y1; ++y)
        for (int x = t.x0; x < t.x1; ++x) ++covered[y * w + x];
    }
    for (int c : covered) ASSERT_EQ(c, 1) << "tile size " << size;
  }
}

TEST(TileScheduler, WavesDoubleUpToTheCapAndSumToTheSampleCount) {
  const std::vector<SampleWave> w = make_sample_waves(200, 64);
  const std::vector<int> sizes = {1, 2, 4, 8, 16, 32, 64, 64, 9};
  ASSERT_EQ(w.size(), sizes.size());
  int next = 0;
  for (std::size_t i = 0; i < w.size(); ++i) {
    EXPECT_EQ(w[i].begin, next);
    EXPECT_EQ(w[i].end - w[i].begin, sizes[i]);
    next = w[i].end;
  }
  EXPECT_EQ(next, 200);
  EXPECT_EQ(make_sample_waves(1).size(), 1u);
}

TEST(TileScheduler, DynamicRunVisitsEveryTileOnce) {
  std::vector<std::atomic<int>> visits(1000);
  run_tiles_dynamic(visits.size(), [&](std::size_t i) { ++visits[i]; });
  for (auto& v : visits) ASSERT_EQ(v.load(), 1);
}

}  // namespace
}  // namespace tessera
