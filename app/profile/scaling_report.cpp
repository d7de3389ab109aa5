#include "app/profile/scaling_report.h"

#include <fmt/format.h>

namespace tessera {

std::string scaling_markdown(const ScalingReport& r) {
  std::string md = fmt::format(
      "Scene `{}`, {}x{}, {} spp, tile {} ({}), median of {} renders; {} cores. Speedup against {:.3f} s, "
      "the median one-thread time over all schedulers. On-CPU: CPU time / busy time of the render threads "
      "(below 100% when other processes took the cores).\n\n",
      r.scene, r.width, r.height, r.spp, r.tile_size, r.tile_order, r.repeat, r.cores, r.baseline);
  // The ranks column only when ranks were swept: a thread sweep's table stays as it was.
  const bool ranks = r.ranks_max > 1;
  if (ranks)
    md += "Runs of several ranks: `tessera render` under the launcher; threads are per rank, and "
          "efficiency is over every rank's threads.\n\n";
  md += fmt::format("| scheduler | {}threads | wall s (median) | min..max s | speedup | speedup / {} | "
                    "parallel efficiency | imbalance | tail s | on-CPU |\n|---|{}---:|---:|---:|---:|---:|---:|---:|"
                    "---:|---:|\n",
                    ranks ? "ranks | " : "", ranks ? "(ranks x threads)" : "threads", ranks ? "---:|" : "");
  for (const ScalingRow& row : r.rows)
    md += fmt::format("| {} | {}{} | {:.3f} | {:.3f}..{:.3f} | {:.2f} | {:.1f}% | {:.1f}% | {:.3f} | {:.3f} "
                      "| {:.0f}% |\n",
                      row.scheduler, ranks ? fmt::format("{} | ", row.ranks) : "", row.threads, row.wall,
                      row.wall_min, row.wall_max, row.speedup, 100.0 * row.speedup / (row.ranks * row.threads),
                      100.0 * row.efficiency, row.imbalance, row.tail, 100.0 * row.cpu_share);
  return md;
}

std::string scaling_csv(const ScalingReport& r) {
  std::string csv = "scene,scheduler,threads,wall_seconds_median,wall_seconds_min,wall_seconds_max,speedup,"
                    "speedup_per_thread,parallel_efficiency,imbalance,tail_seconds,cpu_share,ranks\n";
  for (const ScalingRow& row : r.rows)  // threads: per rank; speedup_per_thread: per thread of all ranks
    csv += fmt::format("{},{},{},{:.6f},{:.6f},{:.6f},{:.4f},{:.4f},{:.4f},{:.4f},{:.6f},{:.4f},{}\n", r.scene,
                       row.scheduler, row.threads, row.wall, row.wall_min, row.wall_max, row.speedup,
                       row.speedup / (row.ranks * row.threads), row.efficiency, row.imbalance, row.tail,
                       row.cpu_share, row.ranks);
  return csv;
}

}  // namespace tessera
