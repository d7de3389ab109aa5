// How the tiles of one sample wave are shared among the threads. Every scheduler hands out
// each work item exactly once per wave, and a pixel belongs to exactly one item, so the
// choice changes timing only, never the image.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "renderer/parallel/tile_order.h"
#include "renderer/parallel/tile_scheduler.h"

namespace tessera {

enum class SchedulerKind {
  tiles,  // TBB parallel_for over tiles, one task each, work stealing (dynamic)
  chunks,  // the paper: n contiguous blocks of rows for n threads, remainder to the last
  counter,  // the paper's proposal: n threads take the next tile from one shared atomic counter
  interleaved,  // static round-robin: thread t renders tiles t, t+n, t+2n, ... (no communication)
};

const char* scheduler_name(SchedulerKind kind);
SchedulerKind parse_scheduler(const std::string& name);  // throws std::invalid_argument
const std::vector<std::string>& scheduler_names();

// What a scheduler hands out: a pixel rectangle inside one tile of the grid. Items are the
// tiles themselves, except for chunks, whose row blocks cut tiles at block boundaries.
struct WorkItem {
  Tile rect;
  int tile;  // row-major index in the tile grid
  int chunk;  // chunks: the block (and thread) it belongs to; otherwise 0
};

struct WorkPlanParams {
  int width = 0, height = 0, tile_size = 32;
  int threads = 1;
  SchedulerKind scheduler = SchedulerKind::tiles;
  TileOrder order = TileOrder::scanline;
};

struct WorkPlan {
  WorkPlanParams params;
  TileGrid grid;
  std::vector<Tile> tiles;  // the grid, row-major
  std::vector<WorkItem> items;  // in the order they are offered (chunks: grouped by block)
  std::vector<std::size_t> chunk_begin;  // chunks: items of block t are [chunk_begin[t], chunk_begin[t+1])
};

WorkPlan make_work_plan(const WorkPlanParams& params);

// First row of each of the n blocks, plus `height` at the end: height / n rows each, the
// remainder to the last block.
std::vector<int> chunk_rows(int height, int threads);

// Called once per item per wave with the index of the thread running it, in [0, threads).
using ItemBody = std::function<void(std::size_t item, int thread)>;

// Runs the waves of one frame with the plan's scheduler and thread count. Holds whatever
// lives for the whole frame (the TBB arena), so each wave only hands out work.
class WaveRunner {
 public:
  explicit WaveRunner(const WorkPlan& plan);
  ~WaveRunner();
  WaveRunner(const WaveRunner&) = delete;
  WaveRunner& operator=(const WaveRunner&) = delete;

  // Returns when every item has run once.
  void run(const ItemBody& body);
  // The items of batches `next` hands out ([begin, end); empty: no more), run by the plan's
  // threads as they come, whatever the scheduler: what a rank of a distributed render runs of
  // the batches it takes from the shared counter. `next` is called on the calling thread
  // only (MPI's), first at once, then whenever fewer items than threads wait to start and
  // this thread has finished an item, so the threads need not wait at a batch's end.
  using NextBatch = std::function<std::pair<std::size_t, std::size_t>()>;
  void run_batches(const NextBatch& next, const ItemBody& body);

 private:
  struct Arena;
  const WorkPlan& plan_;
  std::unique_ptr<Arena> arena_;  // tiles only
};

}  // namespace tessera
