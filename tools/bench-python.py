#!/usr/bin/env python3
"""What the Python package costs per render beyond the renderer's own work (docs/python.md):
renders VIEWS orbit views of a scene read once and, per render, compares the wall time seen from
Python with the native session's own time (posing, building or updating, rendering), so the
difference is argument building, the hand-over to the rendering thread and back, and the
copies into numpy arrays.

    PYTHONPATH=build/python python3 tools/bench-python.py [SCENE] [--views 100] [--size 256] [--spp 16]
"""

import argparse
import statistics
import time

import tessera


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scene", nargs="?", default="scenes/khronos/DamagedHelmet/glTF-Binary/DamagedHelmet.glb")
    parser.add_argument("--views", type=int, default=100)
    parser.add_argument("--size", type=int, default=256)
    parser.add_argument("--spp", type=int, default=16)
    args = parser.parse_args()

    start = time.perf_counter()
    scene = tessera.Scene(args.scene)
    read = time.perf_counter() - start
    rows = []
    for view in range(args.views):
        start = time.perf_counter()
        layers = scene.render(width=args.size, height=args.size, spp=args.spp, seed=view,
                              orbit=(360.0 * view / args.views, 15.0), aovs=["albedo", "normal", "depth"])
        wall = time.perf_counter() - start
        s = layers.stats
        rows.append((wall - s["session_seconds"], s["load_seconds"], s["build_seconds"], s["seconds"], wall))
    overhead, load, build, render, wall = (sorted(column) for column in zip(*rows))

    def ms(values, q):
        return 1e3 * values[min(len(values) - 1, int(q * len(values)))]

    print(f"{args.scene}: read once in {read:.2f} s; {args.views} views, {args.size}x{args.size}, {args.spp} spp, "
          f"layers RGBA, Albedo, N, Z")
    print(f"{'per render (ms)':<28}{'median':>10}{'p90':>10}{'max':>10}")
    for name, values in (("Python's overhead", overhead), ("pose the scene (load)", load),
                         ("update the scene (build)", build), ("render", render), ("wall, as Python sees it", wall)):
        print(f"{name:<28}{ms(values, 0.5):>10.2f}{ms(values, 0.9):>10.2f}{1e3 * values[-1]:>10.2f}")
    print(f"total {sum(wall):.1f} s; Python's overhead {100 * sum(overhead) / sum(wall):.2f}% of it")


if __name__ == "__main__":
    main()
