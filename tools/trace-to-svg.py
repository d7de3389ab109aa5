#!/usr/bin/env python3
"""Draws a Chrome trace-event file (tessera render --trace) as an SVG Gantt chart.

One row per thread, one box per complete ('X') slice, coloured by sample wave, with the wave
boundaries, a time axis in milliseconds and each thread's busy share. What Perfetto or
chrome://tracing shows, as a picture for documents. Standard library only.

Usage: tools/trace-to-svg.py TRACE.json OUT.svg [--title TEXT] [--width PIXELS]
"""

import argparse
import json
import re
import sys

# Alternating blues and oranges: neighbouring waves always differ (Okabe-Ito based).
WAVE_COLOURS = ["#0072B2", "#E69F00", "#56B4E9", "#D55E00", "#009E73", "#CC79A7"]
ROW, GAP, LEFT, RIGHT, TOP, BOTTOM = 26, 8, 150, 20, 56, 50


def esc(text):
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def nice_step(span, most):
    p = 1.0
    while True:
        for m in (1.0, 2.0, 5.0):
            if span / (m * p) <= most:
                return m * p
        p *= 10.0


def load(path):
    with open(path) as f:
        trace = json.load(f)
    events = trace["traceEvents"] if isinstance(trace, dict) else trace
    slices = [e for e in events if e.get("ph") == "X"]
    # A track per (process, thread): under MPI a process per rank, named "rank N".
    processes = {e["pid"]: e["args"]["name"] for e in events if e.get("ph") == "M" and e.get("name") == "process_name"}
    names = {(e["pid"], e["tid"]): e["args"]["name"] for e in events
             if e.get("ph") == "M" and e.get("name") == "thread_name"}
    if len(processes) > 1:
        names = {k: f"{processes.get(k[0], k[0])} {v}" for k, v in names.items()}
    for s in slices:
        s["track"] = (s.get("pid", 1), s["tid"])
    process = next(iter(processes.values()), "") if len(processes) == 1 else f"{len(processes)} ranks"
    waves = sorted(e["ts"] for e in events if e.get("ph") == "i")
    return slices, names, process, waves, trace.get("otherData", {}) if isinstance(trace, dict) else {}


def wave_of(name):
    m = re.search(r"wave (\d+)", name)
    return int(m.group(1)) if m else 0


def draw(slices, names, title, waves, width):
    tids = sorted(set(names) | {s["track"] for s in slices})
    t0 = min([s["ts"] for s in slices] + waves)
    t1 = max(s["ts"] + s["dur"] for s in slices)
    span = max(t1 - t0, 1e-9)
    plot_w = width - LEFT - RIGHT
    height = TOP + len(tids) * (ROW + GAP) + BOTTOM
    x = lambda t: LEFT + (t - t0) / span * plot_w
    row_y = {tid: TOP + i * (ROW + GAP) for i, tid in enumerate(tids)}
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
           f'viewBox="0 0 {width} {height}" font-family="sans-serif" font-size="12">',
           '<rect width="100%" height="100%" fill="white"/>',
           f'<text x="{LEFT}" y="24" font-size="15">{esc(title)}</text>']
    busy = {tid: 0.0 for tid in tids}
    for s in slices:
        busy[s["track"]] += s["dur"]
    for tid in tids:
        y = row_y[tid]
        out.append(f'<rect x="{LEFT}" y="{y}" width="{plot_w}" height="{ROW}" fill="#f0f0f0"/>')
        label = f'{names.get(tid, "thread %d" % tid[1])}  {100.0 * busy[tid] / span:.0f}%'
        out.append(f'<text x="{LEFT - 8}" y="{y + ROW / 2 + 4}" text-anchor="end">{esc(label)}</text>')
    for s in slices:
        colour = WAVE_COLOURS[wave_of(s.get("name", "")) % len(WAVE_COLOURS)]
        w = max(s["dur"] / span * plot_w, 0.3)
        out.append(f'<rect x="{x(s["ts"]):.2f}" y="{row_y[s["track"]]}" width="{w:.2f}" height="{ROW}" '
                   f'fill="{colour}" stroke="white" stroke-width="0.3"><title>{esc(s.get("name", ""))}</title></rect>')
    bottom = TOP + len(tids) * (ROW + GAP) - GAP
    for t in waves:
        out.append(f'<line x1="{x(t):.2f}" y1="{TOP - 6}" x2="{x(t):.2f}" y2="{bottom + 4}" stroke="#333" '
                   'stroke-width="0.6" stroke-dasharray="3 2"/>')
    step = nice_step(span / 1000.0, 10)
    tick = 0.0
    while tick <= span / 1000.0 + 1e-9:
        tx = x(t0 + tick * 1000.0)
        out.append(f'<line x1="{tx:.2f}" y1="{bottom + 4}" x2="{tx:.2f}" y2="{bottom + 10}" stroke="#333"/>')
        out.append(f'<text x="{tx:.2f}" y="{bottom + 24}" text-anchor="middle">{tick:g}</text>')
        tick += step
    out.append(f'<text x="{LEFT + plot_w / 2}" y="{height - 10}" text-anchor="middle">milliseconds since the '
               'first wave started (dashed: sample waves start; colour: wave)</text>')
    out.append("</svg>")
    return "\n".join(out) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("trace")
    ap.add_argument("out")
    ap.add_argument("--title", help="default: the trace's process name and its efficiency")
    ap.add_argument("--width", type=int, default=960)
    args = ap.parse_args()
    slices, names, process, waves, other = load(args.trace)
    if not slices:
        sys.exit(f"{args.trace}: no complete ('X') slices")
    title = args.title
    if title is None:
        title = process
        if "parallel_efficiency" in other:
            title += f": efficiency {100 * other['parallel_efficiency']:.1f}%, imbalance {other['imbalance']:.2f}"
    with open(args.out, "w") as f:
        f.write(draw(slices, names, title, waves, args.width))


if __name__ == "__main__":
    main()
