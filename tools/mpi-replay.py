#!/usr/bin/env python3
"""Predicts a distributed render's wall time and efficiency on N nodes from one frame's
measured tile costs (the replay model of docs/distributed.md).

Reads `tessera render --stats-json` (one process or several ranks): the CPU time of every tile
in every sample wave, which does not depend on what else the measuring machine was doing.
Each wave is replayed on N ranks of T threads each:

  dynamic  tessera's counter (renderer/render/render.cpp): a rank asks rank 0 for a batch of tiles
           (half its share of what is left, and at least T; what is left as the rank can tell:
           the counter past its last batch, and past as many again for each other rank), the
           answer comes one network latency later (plus a service time at rank
           0, which serves one request at a time), the rank runs the batch on its T threads
           (each tile to the first free thread) and asks again; an empty answer ends its wave.
  static   rank r runs the tiles [n r / N, n (r + 1) / N) on its threads.

After its tiles every rank sends the others its pixels (a ring allgather: N - 1 latencies and
(N - 1) / N of the frame's bytes through each node's link), and the ranks agree between waves
(about 7 collective calls, each ceil(log2 N) latencies). A wave lasts as long as its last rank
plus that; the frame is the sum of its waves. Efficiency = CPU time of all tiles / (N x T x
predicted wall).

Left out: loading and BVH building (every node does it at once, before the frame), rank 0's
writing, memory and SMT effects, network contention other than the counter's queue, and
nodes of unequal speed (each thread runs a tile in the measured CPU time).

Usage: tools/mpi-replay.py STATS.json [--nodes 8,64,512] [--threads 64] [--latency-us 30]
         [--bandwidth-gbs 1.25] [--bytes-per-pixel 28] [--frame-scale 1] [--spp S] [--service-us 0.5]
Prints a Markdown table. Standard library only.
"""

import argparse
import heapq
import json
import math
from collections import defaultdict

COLLECTIVES_PER_WAVE = 7  # start_wave's two barriers, the exchange's two, sums and the stop vote


def wave_costs(stats, frame_scale=1):
    """Per wave, the tiles' CPU seconds in tile (scanline) order; the frame `frame_scale` times
    over (a frame that many times larger, of the same tiles)."""
    waves = defaultdict(dict)
    for run in stats["tile_runs"]:
        waves[run["wave"]][run["tile"]] = run["cpu_seconds"]
    return [[waves[w][t] for t in sorted(waves[w])] * frame_scale for w in sorted(waves)]


def extend_to_spp(waves, stats, spp):
    """The waves of an `spp`-sample frame from a shorter measured one: each wave past the
    measured spp is a 64-sample wave, costed as the measured wave with the most samples
    scaled to 64 (a tile's cost is proportional to its samples)."""
    measured = stats["spp"]
    if spp <= measured:
        return waves
    sizes = [w["samples"][1] - w["samples"][0] for w in stats["waves"]]
    big = max(range(len(sizes)), key=lambda w: sizes[w])
    wave64 = [c * 64 / sizes[big] for c in waves[big]]
    return waves + [wave64] * math.ceil((spp - measured) / 64)


def run_batch(costs, threads, start):
    """When `threads` threads, free at `start`, finish `costs` (each to the first free thread)."""
    free = [start] * threads
    for c in costs:
        heapq.heappush(free, heapq.heappop(free) + c)
    return max(free)


def dynamic_makespan(costs, nodes, threads, latency, service):
    """The wave's end under tessera's counter (WaveRunner::run_batches): each rank's threads
    take tiles from its queue; its MPI thread (thread 0), whenever it is free and fewer tiles
    than threads wait, asks for the next batch and waits for the answer, which fills the queue
    (and wakes the threads that ran out); an empty answer means no more."""
    n, share = len(costs), 2 * nodes
    counter, counter_free, end = 0, 0.0, 0.0
    queue = [[] for _ in range(nodes)]  # tiles waiting to start, in order (popped from the front)
    idle = [[] for _ in range(nodes)]  # threads out of work
    more = [True] * nodes
    batch = [max(threads, n // share)] * nodes
    events = [(0.0, r, t, None) for r in range(nodes) for t in range(threads)]  # (time, rank, thread, arrival)
    heapq.heapify(events)

    def start(r, t, now):
        nonlocal end
        if queue[r]:
            heapq.heappush(events, (now + costs[queue[r].pop(0)], r, t, None))
        else:
            idle[r].append(t)
            end = max(end, now)

    while events:
        now, r, t, arrival = heapq.heappop(events)
        if arrival is not None:  # thread 0's answer: the batch joins the queue
            begin, stop = arrival
            queue[r].extend(range(begin, stop))
            woken, idle[r] = sorted(k for k in idle[r] if k != 0), []
            for k in woken:
                start(r, k, now)
            heapq.heappush(events, (now, r, 0, None))  # the MPI thread: ask again, or take a tile
            continue
        if t == 0 and more[r] and len(queue[r]) < threads:
            served = max(now + latency / 2, counter_free) + service
            counter_free = served
            begin, stop = min(counter, n), min(counter + batch[r], n)
            batch[r] = max(threads, (n - min(begin + batch[r] * nodes, n)) // share)
            counter = max(counter, stop)
            if begin >= stop:
                more[r] = False
                end = max(end, served + latency / 2)
                start(r, 0, served + latency / 2)
            else:
                heapq.heappush(events, (served + latency / 2, r, 0, (begin, stop)))
            continue
        start(r, t, now)
    return end


def static_makespan(costs, nodes, threads):
    n = len(costs)
    return max(run_batch(costs[n * r // nodes:n * (r + 1) // nodes], threads, 0.0) for r in range(nodes))


def exchange_seconds(nodes, frame_bytes, latency, bandwidth):
    """After a wave: the ring allgather of every rank's pixels and the collectives around it."""
    if nodes == 1:
        return 0.0
    allgather = (nodes - 1) * latency + frame_bytes * (nodes - 1) / nodes / bandwidth
    return allgather + COLLECTIVES_PER_WAVE * math.ceil(math.log2(nodes)) * latency


def predict(waves, nodes, threads, frame_bytes, latency, bandwidth, service):
    """{scheduler: (wall seconds, efficiency)} and the exchange's share of the dynamic wall."""
    total = sum(sum(w) for w in waves)
    exchange = len(waves) * exchange_seconds(nodes, frame_bytes, latency, bandwidth)
    out = {}
    for name, makespan in (("dynamic", lambda w: dynamic_makespan(w, nodes, threads, latency, service)),
                           ("static", lambda w: static_makespan(w, nodes, threads))):
        wall = sum(makespan(w) for w in waves) + exchange
        out[name] = (wall, total / (nodes * threads * wall) if wall > 0 else 1.0)
    out["exchange_share"] = exchange / out["dynamic"][0] if out["dynamic"][0] > 0 else 0.0
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("stats", help="tessera render --stats-json output")
    parser.add_argument("--nodes", default="8,64,512", help="node (rank) counts, comma-separated")
    parser.add_argument("--threads", type=int, default=0, help="threads per node [default: the measured run's]")
    parser.add_argument("--latency-us", type=float, default=30.0, help="one-way message latency [10 GbE TCP: 30]")
    parser.add_argument("--bandwidth-gbs", type=float, default=1.25, help="each node's link, GB/s [10 GbE: 1.25]")
    parser.add_argument("--service-us", type=float, default=0.5, help="rank 0's time to serve a counter request")
    parser.add_argument("--bytes-per-pixel", type=int, default=28,
                        help="sent per pixel per wave: 28 without AOVs (docs/distributed.md)")
    parser.add_argument("--frame-scale", type=int, default=1, help="replay a frame this many times larger")
    parser.add_argument("--spp", type=int, default=0, help="replay a frame of more samples per pixel than measured")
    a = parser.parse_args()
    with open(a.stats) as f:
        stats = json.load(f)
    waves = extend_to_spp(wave_costs(stats, a.frame_scale), stats, a.spp)
    threads = a.threads or stats["threads"]
    frame_bytes = stats["width"] * stats["height"] * a.bytes_per_pixel * a.frame_scale
    total = sum(sum(w) for w in waves)
    print(f"{a.stats}: {stats['width']}x{stats['height']} x {a.frame_scale}, {max(a.spp, stats['spp'])} spp "
          f"in {len(waves)} waves, "
          f"{len(waves[0]) if waves else 0} tiles a wave, {total:.3f} CPU s of tiles; {threads} threads a node, "
          f"latency {a.latency_us:g} us, {a.bandwidth_gbs:g} GB/s, {frame_bytes / 1e6:.1f} MB a wave\n")
    print("| nodes | dynamic wall s | dynamic efficiency | static wall s | static efficiency | exchange share |")
    print("|---:|---:|---:|---:|---:|---:|")
    for nodes in (int(n) for n in a.nodes.split(",")):
        p = predict(waves, nodes, threads, frame_bytes, a.latency_us * 1e-6, a.bandwidth_gbs * 1e9, a.service_us * 1e-6)
        print(f"| {nodes} | {p['dynamic'][0]:.4g} | {100 * p['dynamic'][1]:.1f}% | {p['static'][0]:.4g} "
              f"| {100 * p['static'][1]:.1f}% | {100 * p['exchange_share']:.1f}% |")


if __name__ == "__main__":
    main()
