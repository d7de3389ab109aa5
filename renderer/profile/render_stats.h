// Where the time of a frame went: per work item and wave, per thread, per wave, and the
// load-balance figures of the whole frame. Collected without locks: every thread writes only
// its own slot, and every item's slot is written by the one thread that runs it.
#pragma once

#include <chrono>
#include <cstdint>
#include <vector>

#include "renderer/parallel/schedulers.h"

namespace tessera {

// One item rendered in one sample wave. Times are seconds since the frame started.
struct TileRecord {
  int item = -1, wave = -1;
  int thread = -1;  // -1: never ran (the frame was cancelled first, or another rank ran it)
  int rank = 0;  // the MPI rank whose thread it was
  double start = 0.0, end = 0.0;
  double cpu = 0.0;  // the thread's CPU time in the tile: less than end - start when preempted
  std::uint64_t samples = 0, rays = 0;
};

struct ThreadStats {
  int rank = 0, thread = 0;  // the MPI rank, and the thread's index in it
  double busy = 0.0;  // inside items
  double idle = 0.0;  // wall time minus busy: waiting for work, at wave ends, or not scheduled
  double cpu = 0.0;  // CPU time inside items: on a shared machine, busy minus time preempted
  std::uint64_t items = 0;
};

struct WaveStats {
  int sample_begin = 0, sample_end = 0;  // samples [begin, end) of every pixel
  double start = 0.0, end = 0.0;
  double tail = 0.0;  // from the first thread running out of work to the end of the wave
};

struct LoadBalance {
  double wall = 0.0;  // seconds from the first wave's start to the last wave's end
  double efficiency = 1.0;  // busy time summed over threads / (threads x wall)
  double imbalance = 1.0;  // max over mean thread busy time
  double tail = 0.0;  // the waves' tails summed: a barrier ends every wave
  double cpu_share = 1.0;  // CPU time / busy time: below 1 when other processes took the cores
};

// One rank of a distributed render, over the frame's wall time (the cluster's).
struct RankStats {
  int rank = 0, threads = 0;
  double busy = 0.0;  // its threads' busy time, summed
  double idle = 0.0;  // threads x wall minus busy
  double communication = 0.0;  // in MPI calls: exchanging films, taking work, waiting for the others
  double cpu = 0.0;
  std::uint64_t items = 0;
  double efficiency = 1.0;  // busy / (threads x wall)
};

struct FrameProfile {
  WorkPlan plan;
  std::vector<WaveStats> waves;
  std::vector<ThreadStats> threads;
  std::vector<double> item_seconds;  // per item, summed over waves: wall time
  std::vector<double> item_cpu_seconds;  // the same in thread CPU time
  std::vector<TileRecord> records;  // waves x items, wave-major; empty unless asked for
  LoadBalance balance;  // a distributed render: over every thread of every rank
  // A distributed render, on rank 0 (empty otherwise): every rank, and for each tile the rank
  // that spent the most CPU time on it (summed over the waves).
  std::vector<RankStats> ranks;
  std::vector<int> tile_rank;
};

// Busy and idle per thread, efficiency, imbalance and tail, from what the threads recorded.
LoadBalance load_balance(const std::vector<ThreadStats>& threads, const std::vector<WaveStats>& waves);

// Wall time is what the scheduler saw; CPU time is what the pixels cost, whatever else the
// machine was doing (a preempted tile's wall time grows, its CPU time does not).
enum class TileClock { wall, cpu };

// Seconds spent on each tile of the grid (row-major), summed over its items and the waves.
std::vector<double> tile_seconds(const FrameProfile& profile, TileClock clock = TileClock::wall);

// A per-pixel image (row-major) of the CPU seconds spent on the pixel's tile.
std::vector<float> tile_cost_image(const FrameProfile& profile);

// Collects a FrameProfile while a frame renders. The driving thread calls begin_wave and
// end_wave between waves; worker threads call record once per item, touching only the
// slots of their own thread and of that item.
class ProfileRecorder {
 public:
  ProfileRecorder(const WorkPlan& plan, int waves, bool record_tiles);

  double now() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }
  static double thread_cpu_seconds();  // CPU time of the calling thread
  void begin_wave(int wave, int sample_begin, int sample_end);
  // `run` holds start, end, cpu, samples and rays; item, wave and thread are filled in here.
  void record(std::size_t item, int thread, const TileRecord& run);
  void end_wave();
  FrameProfile finish();

 private:
  struct alignas(64) ThreadSlot {  // one cache line per thread: no false sharing
    double busy = 0.0, cpu = 0.0, last_end = 0.0;
    std::uint64_t items = 0;
  };
  std::chrono::steady_clock::time_point start_;
  FrameProfile profile_;
  std::vector<ThreadSlot> slots_;
  bool record_tiles_;
  int wave_ = -1;
};

}  // namespace tessera
