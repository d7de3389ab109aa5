// The results of tessera scaling and the files they are written to: a Markdown table and a
// CSV file (the plot of speedup against threads: app/profile/scaling_plot.h).
#pragma once

#include <string>
#include <vector>

namespace tessera {

// One scheduler at one rank and thread count: medians over the repeated renders.
struct ScalingRow {
  std::string scheduler;
  int ranks = 1;  // MPI ranks, each with `threads` threads
  int threads = 0;
  double wall = 0.0, wall_min = 0.0, wall_max = 0.0;  // seconds
  double speedup = 0.0;  // baseline / wall
  double efficiency = 0.0;  // measured: busy time / (ranks x threads x wall)
  double imbalance = 1.0, tail = 0.0;
  double cpu_share = 1.0;  // CPU time / busy time: below 1 when other processes took the cores
};

struct ScalingReport {
  std::string scene;
  int width = 0, height = 0, spp = 0, tile_size = 0, repeat = 0, cores = 0, threads_max = 0;
  int ranks_max = 1;
  std::string tile_order;
  std::vector<std::string> schedulers;
  double baseline = 0.0;  // median one-thread (one-rank) wall time over every scheduler's runs
  std::vector<ScalingRow> rows;  // by scheduler, then ranks, then threads
};

std::string scaling_markdown(const ScalingReport& report);
std::string scaling_csv(const ScalingReport& report);

}  // namespace tessera
