// gather_profile without MPI: two ranks' profiles merged by rank 0 as the ranks would send
// them, through a RankGroup whose gather hands rank 1's bytes to rank 0.
#include <gtest/gtest.h>

#include "renderer/profile/rank_profile.h"

namespace tessera {
namespace {

// One rank of two; rank 1's gather leaves its bytes in the mailbox rank 0's gather returns.
class TwoRanks : public RankGroup {
 public:
  TwoRanks(int rank, std::vector<char>& mailbox) : rank_(rank), mailbox_(mailbox) {}
  int rank() const override { return rank_; }
  int size() const override { return 2; }
  std::vector<std::vector<char>> gather(const std::vector<char>& mine) override {
    if (rank_ == 1) {
      mailbox_ = mine;
      return {};
    }
    return {mine, mailbox_};
  }
  void start_wave(std::size_t) override {}
  std::pair<std::size_t, std::size_t> next_items(std::size_t) override { return {0, 0}; }
  std::vector<std::vector<char>> all_gather(const std::vector<char>&) override { return {}; }
  bool any(bool flag) override { return flag; }
  std::uint64_t sum(std::uint64_t value) override { return value; }
  void barrier() override {}
  void alive() override {}
  void progress() override {}
  double communication_seconds() const override { return 0.0; }

 private:
  int rank_;
  std::vector<char>& mailbox_;
};

// Two tiles, one wave, one thread: this rank ran `item` from `start` to `end`.
FrameProfile one_run(int item, double start, double end, double wave_end, double tail) {
  FrameProfile p;
  p.plan = make_work_plan({64, 32, 32, 1});
  p.item_seconds.assign(2, 0.0);
  p.item_cpu_seconds.assign(2, 0.0);
  p.item_seconds[item] = p.item_cpu_seconds[item] = end - start;
  p.waves = {{0, 1, start, wave_end, tail}};
  ThreadStats t;
  t.busy = t.cpu = end - start;
  t.items = 1;
  p.threads = {t};
  p.records.resize(2);
  for (int i = 0; i < 2; ++i) p.records[i].item = i, p.records[i].wave = 0;
  p.records[item].thread = 0;
  p.records[item].start = start;
  p.records[item].end = end;
  return p;
}

TEST(GatherProfile, RankZeroMergesEveryRanksThreadsWavesAndRuns) {
  std::vector<char> mailbox;
  TwoRanks one(1, mailbox), zero(0, mailbox);
  const FrameProfile mine1 = gather_profile(one, one_run(1, 0.1, 1.0, 1.1, 0.5), 0.25);
  EXPECT_TRUE(mine1.ranks.empty()) << "rank 1 keeps its own profile";
  const FrameProfile p = gather_profile(zero, one_run(0, 0.0, 0.4, 1.0, 0.6), 0.5);
  ASSERT_EQ(p.threads.size(), 2u);
  EXPECT_EQ(p.threads[1].rank, 1);
  // The wave spans both ranks; its tail runs from rank 0's thread running out (0.4) to 1.1.
  ASSERT_EQ(p.waves.size(), 1u);
  EXPECT_DOUBLE_EQ(p.waves[0].start, 0.0);
  EXPECT_DOUBLE_EQ(p.waves[0].end, 1.1);
  EXPECT_NEAR(p.waves[0].tail, 0.7, 1e-12);
  EXPECT_NEAR(p.balance.wall, 1.1, 1e-12);
  EXPECT_NEAR(p.balance.efficiency, (0.4 + 0.9) / (2 * 1.1), 1e-12);
  ASSERT_EQ(p.ranks.size(), 2u);
  EXPECT_NEAR(p.ranks[0].idle, 1.1 - 0.4, 1e-12);
  EXPECT_DOUBLE_EQ(p.ranks[1].communication, 0.25);
  EXPECT_NEAR(p.ranks[1].efficiency, 0.9 / 1.1, 1e-12);
  // Each tile's run and cost, from the rank that ran it.
  EXPECT_EQ(p.records[0].rank, 0);
  EXPECT_EQ(p.records[1].rank, 1);
  EXPECT_DOUBLE_EQ(p.records[1].end, 1.0);
  EXPECT_EQ(p.tile_rank, (std::vector<int>{0, 1}));
  EXPECT_NEAR(p.item_cpu_seconds[1], 0.9, 1e-12);
}

}  // namespace
}  // namespace tessera
