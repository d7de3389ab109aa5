#!/usr/bin/env bash
# Measures issue 12's targets (docs/distributed.md, "Measured"): on each benchmark scene, 2 MPI
# ranks of 1 thread against 1 process of 2 threads, ROUNDS alternating rounds of rank 0's
# `M samples/s` and the ratio of their medians (target: at least 95%); then the adversarial
# scene on 2 ranks x 1 thread with the counter and with static blocks, alternating, their
# cluster efficiency (targets: the counter at least 97%, static blocks at least 20 points less).
# On a busy machine the other processes decide the figures: run it when nothing else runs.
#   tools/mpi-targets.sh [--rounds N] [--adversarial-rounds N] [--out DIR]
# Needs: mpirun (openmpi-bin) and a build with MPI (build/tessera, or TESSERA=path).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
tessera="${TESSERA:-$root/build/tessera}"
source "$root/tools/measure-lib.sh"
usage="usage: $0 [--rounds N] [--adversarial-rounds N] [--out DIR]"
rounds=3 adversarial_rounds=2 out=/tmp/tessera-mpi-targets
while [[ $# -gt 0 ]]; do
  case "$1" in
    --rounds) rounds=$2; shift 2 ;;
    --adversarial-rounds) adversarial_rounds=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    *) echo "$usage" >&2; exit 2 ;;
  esac
done
mkdir -p "$out"
mpi=(mpirun --oversubscribe --bind-to none -np 2)
[[ $(id -u) -eq 0 ]] && mpi+=(--allow-run-as-root)

# run PATTERN COMMAND...: the sed pattern's group in the first line of the command's messages
# that matches it.
run() {
  local pattern=$1
  shift
  if ! "$@" >"$out/run.log" 2>&1; then
    echo "failed: $*" >&2
    cat "$out/run.log" >&2
    exit 1
  fi
  local value
  value=$(sed -n "s/.*$pattern.*/\\1/p" "$out/run.log" | head -1)
  [[ -n "$value" ]] || { echo "no '$pattern' in the messages of: $*" >&2; cat "$out/run.log" >&2; exit 1; }
  echo "$value"
}
rate='tile [0-9]*: \([0-9.]*\) M samples\/s'  # the summary, not the progress lines
efficiency='cluster efficiency \([0-9.]*\)%'

echo "| scene (320 wide) | spp | 1 rank x 2 threads | 2 ranks x 1 thread | ratio of medians |"
echo "|---|---:|---|---|---:|"
for spec in "cornell-box/cornell-box.gltf 64" \
            "khronos/DamagedHelmet/glTF-Binary/DamagedHelmet.glb 64" \
            "khronos/MetalRoughSpheresNoTextures/glTF-Binary/MetalRoughSpheresNoTextures.glb 128" \
            "khronos/MetalRoughSpheresNoTextures/glTF-Binary/MetalRoughSpheresNoTextures.glb 512" \
            "paper/three-balls.gltf 64" \
            "paper/grid-of-spheres.gltf 64"; do
  read -r scene spp <<<"$spec"
  args=(render "$root/scenes/$scene" --width 320 --spp "$spp" -o "$out/frame.exr")
  one=() two=()
  for ((r = 0; r < rounds; ++r)); do
    one+=("$(run "$rate" "$tessera" "${args[@]}" --threads 2)")
    two+=("$(run "$rate" "${mpi[@]}" "$tessera" "${args[@]}" --threads 1)")
  done
  a=$(printf '%s\n' "${one[@]}" | median) b=$(printf '%s\n' "${two[@]}" | median)
  name=$(basename "$scene" | sed 's/\.gl[tb]f*$//')
  echo "| $name | $spp | ${one[*]} | ${two[*]} | $(awk -v a="$a" -v b="$b" 'BEGIN {printf "%.1f%%", 100 * b / a}') |"
done

echo
echo "adversarial scene, 2 ranks x 1 thread, 320 wide, 64 spp: cluster efficiency"
adversarial=(render "$root/scenes/paper/adversarial.gltf" --width 320 --spp 64 --threads 1 -o "$out/frame.exr")
for ((r = 0; r < adversarial_rounds; ++r)); do
  for scheduler in dynamic static; do
    e=$(run "$efficiency" "${mpi[@]}" "$tessera" "${adversarial[@]}" --rank-scheduler "$scheduler")
    echo "$scheduler: $e%"
  done
done
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg)"
