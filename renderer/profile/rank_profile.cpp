#include "renderer/profile/rank_profile.h"

#include <algorithm>

#include "renderer/util/byte_stream.h"

namespace tessera {
namespace {

std::vector<char> pack_profile(const FrameProfile& p, double communication) {
  ByteWriter out;
  out.put(communication);
  out.put_vector(p.threads);
  out.put_vector(p.waves);
  out.put_vector(p.item_seconds);
  out.put_vector(p.item_cpu_seconds);
  std::vector<TileRecord> ran;  // the runs of this rank's threads only
  std::copy_if(p.records.begin(), p.records.end(), std::back_inserter(ran), [](const TileRecord& r) { return r.thread >= 0; });
  out.put_vector(ran);
  return out.take();
}

struct RankProfile {
  double communication = 0.0;
  std::vector<ThreadStats> threads;
  std::vector<WaveStats> waves;
  std::vector<double> item_seconds, item_cpu_seconds;
  std::vector<TileRecord> runs;
};

RankProfile unpack_profile(const std::vector<char>& bytes) {
  ByteReader in(bytes, "a rank's profile");
  RankProfile p;
  in.get(p.communication);
  p.threads = in.get_vector<ThreadStats>();
  p.waves = in.get_vector<WaveStats>();
  p.item_seconds = in.get_vector<double>();
  p.item_cpu_seconds = in.get_vector<double>();
  p.runs = in.get_vector<TileRecord>();
  return p;
}

// The ranks ran the same waves: each merged wave spans them all, and its tail runs from the
// first thread of any rank running out of work to the last rank's end.
void merge_waves(std::vector<WaveStats>& merged, const std::vector<WaveStats>& rank, bool first) {
  if (first) {
    merged = rank;
    return;
  }
  for (std::size_t w = 0; w < std::min(merged.size(), rank.size()); ++w) {
    WaveStats& m = merged[w];
    const double first_out = std::min(m.end - m.tail, rank[w].end - rank[w].tail);
    m.start = std::min(m.start, rank[w].start);
    m.end = std::max(m.end, rank[w].end);
    m.tail = m.end - first_out;
  }
}

// For each tile, the rank that spent the most CPU time on it.
std::vector<int> busiest_rank(const WorkPlan& plan, const std::vector<std::vector<double>>& rank_item_cpu) {
  std::vector<int> owner(plan.tiles.size(), 0);
  std::vector<double> most(plan.tiles.size(), -1.0);
  for (std::size_t r = 0; r < rank_item_cpu.size(); ++r) {
    std::vector<double> tile(plan.tiles.size(), 0.0);
    for (std::size_t i = 0; i < plan.items.size() && i < rank_item_cpu[r].size(); ++i)
      tile[plan.items[i].tile] += rank_item_cpu[r][i];
    for (std::size_t t = 0; t < tile.size(); ++t)
      if (tile[t] > most[t]) most[t] = tile[t], owner[t] = static_cast<int>(r);
  }
  return owner;
}

}  // namespace

FrameProfile gather_profile(RankGroup& ranks, FrameProfile mine, double communication) {
  const std::vector<std::vector<char>> all = ranks.gather(pack_profile(mine, communication));
  if (ranks.rank() != 0) return mine;
  FrameProfile merged;
  merged.plan = std::move(mine.plan);
  const std::size_t items = merged.plan.items.size();
  merged.item_seconds.assign(items, 0.0);
  merged.item_cpu_seconds.assign(items, 0.0);
  const bool recorded = !mine.records.empty();
  merged.records.resize(mine.records.size());
  std::vector<std::vector<double>> rank_item_cpu;
  for (int r = 0; r < ranks.size(); ++r) {
    RankProfile p = unpack_profile(all[r]);
    merge_waves(merged.waves, p.waves, r == 0);
    RankStats rs;
    rs.rank = r;
    rs.threads = static_cast<int>(p.threads.size());
    rs.communication = p.communication;
    for (ThreadStats& t : p.threads) {
      t.rank = r;
      rs.busy += t.busy;
      rs.cpu += t.cpu;
      rs.items += t.items;
      merged.threads.push_back(t);
    }
    merged.ranks.push_back(rs);
    for (std::size_t i = 0; i < items && i < p.item_seconds.size() && i < p.item_cpu_seconds.size(); ++i) {
      merged.item_seconds[i] += p.item_seconds[i];
      merged.item_cpu_seconds[i] += p.item_cpu_seconds[i];
    }
    for (const TileRecord& run : p.runs) {
      const std::size_t slot = static_cast<std::size_t>(run.wave) * items + run.item;
      if (!recorded || run.item < 0 || static_cast<std::size_t>(run.item) >= items || slot >= merged.records.size())
        continue;
      merged.records[slot] = run;
      merged.records[slot].rank = r;
    }
    rank_item_cpu.push_back(std::move(p.item_cpu_seconds));
  }
  for (std::size_t i = 0; i < merged.records.size(); ++i)  // the runs no rank made say which they were
    if (merged.records[i].thread < 0) merged.records[i] = mine.records[i];
  merged.balance = load_balance(merged.threads, merged.waves);
  for (ThreadStats& t : merged.threads) t.idle = merged.balance.wall - t.busy;
  for (RankStats& rs : merged.ranks) {
    rs.idle = rs.threads * merged.balance.wall - rs.busy;
    if (rs.threads > 0 && merged.balance.wall > 0.0) rs.efficiency = rs.busy / (rs.threads * merged.balance.wall);
  }
  merged.tile_rank = busiest_rank(merged.plan, rank_item_cpu);
  return merged;
}

}  // namespace tessera
