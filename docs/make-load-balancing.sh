#!/usr/bin/env bash
# Measures every table and draws every figure of docs/load-balancing.md (run from anywhere):
#   scaling  tessera scaling on each shipped scene (1..4 threads, every scheduler)
#   figures  each scene's picture, heat maps and traces at 2 threads (tiles and chunks)
#   orders   the tile orders on the adversarial scene at 2 threads
#   model    each scheduler's speedup on 1..16 idle cores, replayed from measured tile costs
#
#   docs/make-load-balancing.sh                    # uses build/tessera (./tessera builds it)
#   TESSERA=build-sched/tessera REPEAT=5 STAGES="figures model" docs/make-load-balancing.sh
#
# Needs python3 (tools/trace-to-svg.py, tools/schedule-model.py). About 15 minutes on 2
# shared cores with REPEAT=5.
# shellcheck source=docs/prelude.sh
source "$(dirname "${BASH_SOURCE[0]}")/prelude.sh"
repeat=${REPEAT:-5}
stages=${STAGES:-scaling figures orders model}
sky=scenes/paper/sky-gradient.hdr
out=docs/load-balancing
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p docs/images "$out"

# name | scene file | options shared by every run of it
scenes=(
  "cornell-box|scenes/cornell-box/cornell-box.gltf|--width 320 --spp 16"
  "timing-scene|scenes/paper/timing-scene.gltf|--width 480 --spp 16 --envmap $sky"
  "adversarial|scenes/paper/adversarial.gltf|--width 480 --spp 16 --envmap $sky"
)

scaling() {  # name scene opts
  echo "== $1: scaling, 1..4 threads, every scheduler, $repeat repeats" >&2
  # shellcheck disable=SC2086
  "$bin" scaling "$2" $3 --threads-max 4 --repeat "$repeat" --out "$out/$1" >/dev/null
}

figures() {  # name scene opts: the picture, then heat map and trace per scheduler
  echo "== $1: heat maps and traces at 2 threads" >&2
  for sched in tiles chunks; do
    # shellcheck disable=SC2086
    "$bin" render "$2" $3 --threads 2 --scheduler "$sched" -q -o "$tmp/$1-$sched.png" \
      --heatmap "docs/images/heatmap-$1-$sched.png" --trace "$tmp/trace-$1-$sched.json"
    python3 tools/trace-to-svg.py "$tmp/trace-$1-$sched.json" "docs/images/trace-$1-$sched.svg"
  done
  cp "$tmp/$1-tiles.png" "docs/images/lb-$1.png"
  if [[ $1 == adversarial ]]; then  # kept for opening in Perfetto
    cp "$tmp/trace-$1-tiles.json" "$tmp/trace-$1-chunks.json" "$out/$1/"
  fi
}

orders() {
  echo "== adversarial: tile orders at 2 threads, $repeat repeats" >&2
  for i in $(seq "$repeat"); do
    for order in scanline spiral hilbert; do
      for sched in tiles counter interleaved; do
        "$bin" render scenes/paper/adversarial.gltf --width 480 --spp 16 --envmap "$sky" --threads 2 -q \
          --scheduler "$sched" --tile-order "$order" -o "$tmp/o.exr" --stats-json "$tmp/order-$sched-$order-$i.json"
      done
    done
  done
  python3 - "$tmp" "$repeat" >"$out/adversarial/tile-orders.md" <<'PY'
import json, statistics, sys
tmp, repeat = sys.argv[1], int(sys.argv[2])
print("| scheduler | tile order | wall s | parallel efficiency | imbalance | tail s |")
print("|---|---|---:|---:|---:|---:|")
for sched in ("tiles", "counter", "interleaved"):
    for order in ("scanline", "spiral", "hilbert"):
        runs = [json.load(open(f"{tmp}/order-{sched}-{order}-{i}.json"))["frame"] for i in range(1, repeat + 1)]
        med = lambda k: statistics.median(r[k] for r in runs)
        print(f"| {sched} | {order} | {med('wall_seconds'):.3f} | {100 * med('parallel_efficiency'):.1f}% | "
              f"{med('imbalance'):.3f} | {med('tail_seconds'):.3f} |")
PY
}

model() {  # name scene opts: one profile with 8-pixel tiles per scene, replayed on 1..16 cores
  echo "== $1: tile costs for the model" >&2
  # shellcheck disable=SC2086
  "$bin" render "$2" $3 --threads 2 --tile-size 8 -q -o "$tmp/m.exr" --stats-json "$tmp/$1.json"
}

for stage in $stages; do
  for entry in "${scenes[@]}"; do
    IFS='|' read -r name scene opts <<<"$entry"
    case $stage in
      scaling | figures | model) "$stage" "$name" "$scene" "$opts" ;;
    esac
  done
  case $stage in
    orders) orders ;;
    model)
      files=("$tmp/cornell-box.json" "$tmp/timing-scene.json" "$tmp/adversarial.json")
      python3 tools/schedule-model.py "${files[@]}" --tile 32 >"$out/schedule-model.md"
      python3 tools/schedule-model.py "${files[@]}" --tile 16 >"$out/schedule-model-tile16.md"
      ;;
  esac
done
echo "make-load-balancing.sh: done" >&2
