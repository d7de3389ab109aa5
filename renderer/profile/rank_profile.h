// The profile of a distributed render: every rank's threads, waves and tile runs, gathered
// to rank 0 after the frame, so --stats-json, --trace, --heatmap and the summary describe the
// whole cluster. The ranks started their clocks together (a barrier), so their times share
// one time line, to within the barrier's latency.
#pragma once

#include "renderer/parallel/rank_group.h"
#include "renderer/profile/render_stats.h"

namespace tessera {

// Collective. On rank 0: every rank's threads (in rank order), the waves from the first
// rank's start to the last rank's end, the items' times summed, every tile run with its rank,
// per-rank busy, idle and communication time, and the load balance over all the threads. On
// the others: `mine`. `communication`: this rank's seconds in MPI calls during the frame.
FrameProfile gather_profile(RankGroup& ranks, FrameProfile mine, double communication);

}  // namespace tessera
