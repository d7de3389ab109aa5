#!/usr/bin/env python3
"""Predicts each scheduler's speedup on 1..N idle cores from one frame's measured tile costs.

On a shared machine the measured speedup says more about the neighbours than about the
scheduler. The CPU time of every tile in every wave (tessera render --stats-json, which
records each tile run's thread CPU time) does not depend on them, so this replays the frame
on n ideal cores: per sample wave, every scheduler's assignment of those costs to n threads,
the wave lasting as long as its busiest thread. Speedup = total CPU time / the sum of the
waves' makespans. What it leaves out: scheduling overhead, memory and SMT effects.

  dynamic      tiles and counter: the next tile (scanline order) to the first free thread
  interleaved  tile i to thread i mod n
  chunks       the paper's blocks of rows: height // n rows each, the remainder to the last

Record the profile with small tiles (e.g. --tile-size 8): chunks are costed per pixel row
(a tile's cost spread evenly over its rows), the others use --tile TILE-pixel tiles built
from the small ones (TILE must be a multiple of the recorded tile size).

Usage: tools/schedule-model.py STATS.json [STATS.json ...] [--tile 32] [--threads 1,2,4,8,16]
Prints a Markdown table (one row per file and scheduler). Standard library only.
"""

import argparse
import heapq
import json
import os
from collections import defaultdict


def wave_costs(stats):
    """{wave: [(x0, y0, x1, y1, cpu_seconds)]} from the recorded tile runs."""
    waves = defaultdict(list)
    for run in stats["tile_runs"]:
        waves[run["wave"]].append((*run["rect"], run["cpu_seconds"]))
    return waves


def coarse_tiles(runs, width, tile):
    """Costs of tile x tile blocks in scanline order, summed from the recorded small tiles."""
    cost = defaultdict(float)
    for x0, y0, x1, y1, cpu in runs:
        cost[(y0 // tile, x0 // tile)] += cpu
    return [cost[k] for k in sorted(cost)]


def dynamic(costs, n):
    free = [0.0] * n  # when each thread is next free; the first free one takes the next tile
    for c in costs:
        heapq.heapreplace(free, free[0] + c)
    return max(free)


def interleaved(costs, n):
    return max(sum(costs[t::n]) for t in range(n))


def chunks(runs, height, n):
    row = [0.0] * height
    for x0, y0, x1, y1, cpu in runs:
        for y in range(y0, y1):
            row[y] += cpu / (y1 - y0)
    per = height // n
    starts = [i * per for i in range(n)] + [height]
    return max(sum(row[starts[i]:starts[i + 1]]) for i in range(n))


def predict(stats, tile, counts):
    waves = wave_costs(stats)
    total = sum(cpu for runs in waves.values() for *_, cpu in runs)
    out = {}
    for n in counts:
        span = defaultdict(float)
        for runs in waves.values():
            costs = coarse_tiles(runs, stats["width"], tile)
            span["dynamic"] += dynamic(costs, n)
            span["interleaved"] += interleaved(costs, n)
            span["chunks"] += chunks(runs, stats["height"], n)
        for name, s in span.items():
            out.setdefault(name, []).append(total / s)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("stats", nargs="+")
    ap.add_argument("--tile", type=int, default=32)
    ap.add_argument("--threads", default="1,2,4,8,16")
    args = ap.parse_args()
    counts = [int(n) for n in args.threads.split(",")]
    print("| scene | scheduler | " + " | ".join(f"{n} cores" for n in counts) + " |")
    print("|---|---|" + "---:|" * len(counts))
    for path in args.stats:
        stats = json.load(open(path))
        if stats["tile_size"] > args.tile or args.tile % stats["tile_size"]:
            raise SystemExit(f"{path}: recorded with tile size {stats['tile_size']}, not a divisor of {args.tile}")
        name = os.path.splitext(os.path.basename(path))[0]
        for sched, speedups in predict(stats, args.tile, counts).items():
            cells = " | ".join(f"{s:.2f}x ({100 * s / n:.0f}%)" for s, n in zip(speedups, counts))
            print(f"| {name} | {sched} | {cells} |")


if __name__ == "__main__":
    main()
