// Every scheduler, tile order and thread count hands out each pixel exactly once per sample
// wave and gives the same image bit for bit; the orders and the chunks' row blocks are what
// they claim to be.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <numeric>

#include "renderer/parallel/schedulers.h"
#include "tests/same_bits.h"
#include "tests/schedule_fixture.h"

namespace tessera {
namespace {

using test::same_bits;

std::string describe(const test::ScheduleCase& c) {
  return std::string(scheduler_name(c.scheduler)) + "/" + tile_order_name(c.order) + "/" + std::to_string(c.threads) +
         " threads";
}

TEST(TileOrder, EveryOrderIsAPermutationOfTheGrid) {
  for (TileGrid g : {TileGrid{1, 1}, TileGrid{7, 3}, TileGrid{8, 8}, TileGrid{2, 13}, TileGrid{30, 17}})
    for (TileOrder o : test::all_tile_orders()) {
      std::vector<int> order = tile_order(g, o);
      std::sort(order.begin(), order.end());
      std::vector<int> expected(static_cast<std::size_t>(g.columns) * g.rows);
      std::iota(expected.begin(), expected.end(), 0);
      EXPECT_EQ(order, expected) << tile_order_name(o) << " " << g.columns << "x" << g.rows;
    }
}

TEST(TileOrder, SpiralStartsAtTheCentreAndMovesOutwards) {
  const TileGrid g{9, 5};
  const std::vector<int> order = tile_order(g, TileOrder::spiral);
  EXPECT_EQ(order.front(), 2 * 9 + 4);  // the centre tile
  auto ring = [&](int t) { return std::max(std::abs(t % 9 - 4), std::abs(t / 9 - 2)); };
  for (std::size_t i = 1; i < order.size(); ++i) EXPECT_GE(ring(order[i]), ring(order[i - 1]));
}

TEST(TileOrder, HilbertStepsOnlyBetweenNeighbours) {
  const TileGrid g{16, 16};
  const std::vector<int> order = tile_order(g, TileOrder::hilbert);
  for (std::size_t i = 1; i < order.size(); ++i) {
    const int dx = std::abs(order[i] % 16 - order[i - 1] % 16), dy = std::abs(order[i] / 16 - order[i - 1] / 16);
    EXPECT_EQ(dx + dy, 1) << "step " << i;
  }
  EXPECT_EQ(order.front(), 0);
}

TEST(TileOrder, NamesRoundTrip) {
  for (TileOrder o : test::all_tile_orders()) EXPECT_EQ(parse_tile_order(tile_order_name(o)), o);
  for (SchedulerKind k : test::all_schedulers()) EXPECT_EQ(parse_scheduler(scheduler_name(k)), k);
  EXPECT_THROW(parse_scheduler("guided"), std::invalid_argument);
  EXPECT_THROW(parse_tile_order("random"), std::invalid_argument);
}

TEST(Chunks, RowBlocksAreEqualWithTheRemainderToTheLast) {
  EXPECT_EQ(chunk_rows(37, 3), (std::vector<int>{0, 12, 24, 37}));
  EXPECT_EQ(chunk_rows(8, 8), (std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7, 8}));
  EXPECT_EQ(chunk_rows(2, 4), (std::vector<int>{0, 0, 0, 0, 2}));  // more threads than rows
}

TEST(WorkPlan, EveryPixelIsInExactlyOneItemForEverySchedulerAndOrder) {
  for (SchedulerKind k : test::all_schedulers())
    for (TileOrder o : test::all_tile_orders())
      for (int threads : {1, 3, 5}) {
        const WorkPlan plan = make_work_plan({45, 37, 8, threads, k, o});
        std::vector<int> covered(45 * 37, 0);
        for (const WorkItem& item : plan.items) {
          const Tile& t = plan.tiles[item.tile];  // an item never leaves its tile
          EXPECT_TRUE(item.rect.x0 >= t.x0 && item.rect.x1 <= t.x1 && item.rect.y0 >= t.y0 && item.rect.y1 <= t.y1);
          for (int y = item.rect.y0; y < item.rect.y1; ++y)
            for (int x = item.rect.x0; x < item.rect.x1; ++x) ++covered[y * 45 + x];
        }
        for (int c : covered) ASSERT_EQ(c, 1) << scheduler_name(k) << " " << tile_order_name(o) << " " << threads;
      }
}

TEST(WorkPlan, ChunkItemsStayInsideTheirBlockOfRows) {
  const WorkPlan plan = make_work_plan({45, 37, 8, 3, SchedulerKind::chunks, TileOrder::hilbert});
  const std::vector<int> rows = chunk_rows(37, 3);
  ASSERT_EQ(plan.chunk_begin.size(), 4u);
  EXPECT_EQ(plan.chunk_begin.back(), plan.items.size());
  for (int c = 0; c < 3; ++c)
    for (std::size_t i = plan.chunk_begin[c]; i < plan.chunk_begin[c + 1]; ++i) {
      EXPECT_EQ(plan.items[i].chunk, c);
      EXPECT_GE(plan.items[i].rect.y0, rows[c]);
      EXPECT_LE(plan.items[i].rect.y1, rows[c + 1]);
    }
}

TEST(Schedulers, EverySchedulerOrderAndThreadCountGivesTheSameBits) {
  const FrameImage reference = test::render_schedule_case({}).image;
  for (SchedulerKind k : test::all_schedulers())
    for (TileOrder o : test::all_tile_orders())
      for (int threads : {2, 3}) {
        const test::ScheduleCase c{k, o, threads};
        const FrameImage img = test::render_schedule_case(c).image;
        EXPECT_TRUE(same_bits(img.rgb, reference.rgb)) << describe(c);
        EXPECT_TRUE(same_bits(img.albedo, reference.albedo)) << describe(c);
        EXPECT_TRUE(same_bits(img.normal, reference.normal)) << describe(c);
        EXPECT_TRUE(same_bits(img.depth, reference.depth)) << describe(c);
        EXPECT_EQ(img.samples_per_pixel, 7) << describe(c);
      }
}

TEST(Schedulers, MoreThreadsThanCoresAndTilesStillGiveTheSameBits) {
  // 6 threads on any machine, and chunks of 6 rows: some threads get a tile or nothing.
  const FrameImage reference = test::render_schedule_case({}).image;
  for (SchedulerKind k : test::all_schedulers()) {
    const test::ScheduleCase c{k, TileOrder::spiral, 6, 32};
    const RenderResult r = test::render_schedule_case(c);
    EXPECT_TRUE(same_bits(r.image.rgb, reference.rgb)) << describe(c);
    EXPECT_EQ(r.stats.threads, 6);
    EXPECT_EQ(r.profile.threads.size(), 6u);
  }
}

}  // namespace
}  // namespace tessera
