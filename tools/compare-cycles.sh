#!/usr/bin/env bash
# Renders glTF scenes with tessera and with Blender Cycles at matched settings (8 bounces, no
# adaptive sampling or denoising in Cycles, 2 threads, same camera, size and samples; a uniform
# white world of radiance 1, or with --envmap that image as the world), each with seed 1 and
# seed 2, alternating A B A B, and prints a Markdown table per scene of
#   - render seconds (median of all 2 x ROUNDS renders per renderer) and camera samples/s;
#   - noise variance at equal spp: mean over pixels and RGB of (seed 1 - seed 2)^2 / 2;
#   - time to equal noise: seconds x noise variance (for an unbiased renderer the variance
#     falls as 1/samples, so this product does not depend on the spp: lower is better), and
#     Cycles' over tessera's: > 1 means tessera reaches a given noise sooner; and the same
#     ratio for the noise normalised by the image's squared mean value, which does not reward
#     the darker image for being darker, and for the relative noise (each pixel's over its own
#     squared value + 0.01, as relMSE weighs errors), which does not reward a renderer for
#     showing a region darker (Cycles' rough metals lose light that tessera keeps), and the same
#     with the regulariser scaled by the image's mean (scale-free: Blender's importer converts
#     punctual light units, so its image of a lamp-lit scene is darker by a constant factor).
# Also writes, per scene, NAME-tessera-vs-cycles.png (seed 1: tessera left, Cycles right) into
# OUT_DIR. Each run's times go to stderr.
#   tools/compare-cycles.sh [--spp N] [--width W] [--height H] [--rounds R] [--out DIR] [--envmap FILE]
#                           [--unbiased] [--black-world] SCENE... [-- TESSERA_OPTION...]
# --unbiased turns Cycles' clamps (indirect 10) and glossy filter off, so that both renderers
# are unbiased (the fair comparison where fireflies matter: glass, small lights); --black-world
# renders both under a black world instead of the white one (scenes lit by their own lights).
# TESSERA_OPTIONs go to every tessera render (e.g. -- --sampler independent; the adaptive
# branch's --noise-threshold 0.01 --min-spp 16). Needs: apt-get install blender
# python3-numpy python3-openimageio openimageio-tools; a built tessera (TESSERA=path, default
# build/tessera).
# Render time is each renderer's own, from its EXR header (tessera: renderTimeSeconds; Cycles:
# render_time), without start-up, scene import or BVH build.
# shellcheck disable=SC2054  # commas inside option values (1,1,1; albedo,normal) are meant
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
tessera="${TESSERA:-$root/build/tessera}"
source "$root/tools/measure-lib.sh"
usage="usage: $0 [--spp N] [--width W] [--height H] [--rounds R] [--out DIR] [--envmap FILE] [--unbiased] [--black-world] SCENE... [-- TESSERA_OPTION...]"
spp=64 width=640 height=360 rounds=3 out=/tmp/tessera-vs-cycles envmap=""
while [[ $# -gt 0 && "$1" == --?* ]]; do
  case "$1" in
    --spp) spp=$2; shift 2 ;;
    --width) width=$2; shift 2 ;;
    --height) height=$2; shift 2 ;;
    --rounds) rounds=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --envmap) envmap=$(realpath -e "$2"); shift 2 ;;
    --unbiased) export CUNBIASED=1; shift ;;
    --black-world) export CWORLD=0; shift ;;
    *) echo "unknown option $1; $usage" >&2; exit 2 ;;
  esac
done
scenes=()
while [[ $# -gt 0 && "$1" != -- ]]; do scenes+=("$1"); shift; done
[[ $# -gt 0 ]] && shift  # the --
tessera_extra=("$@")
[[ ${#scenes[@]} -gt 0 ]] || { echo "$usage" >&2; exit 2; }
mkdir -p "$out"

world=(--background 1,1,1)
[[ "${CWORLD:-1}" == 0 ]] && world=(--background 0)
[[ -n "$envmap" ]] && world=(--envmap "$envmap")
samples=$((width * height * spp))
echo "load before: $(uptime)" >&2
echo "| scene | tessera s | Cycles s | tessera M samples/s | Cycles M samples/s | noise tessera | noise Cycles | s x noise tessera | s x noise Cycles | time to equal noise, Cycles / tessera | same, normalised noise | same, relative noise | same, scale-free relative noise |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
for scene in "${scenes[@]}"; do
  name=$(basename "${scene%.*}")
  t_times=() c_times=()
  for ((r = 0; r < rounds; ++r)); do
    for seed in 1 2; do
      tessera_render "$out/$name-tessera-s$seed.exr" "$scene" --width "$width" --height "$height" --spp "$spp" \
        --max-bounces 8 --threads 2 --seed "$seed" "${world[@]}" >/dev/null
      t_times+=("$(metrics render-time "$out/$name-tessera-s$seed.exr")")
      cycles_render "$out/$name-cycles-s$seed.exr" "$scene" "$spp" "$width" "$height" "$seed" "$envmap"
      c_times+=("$(metrics render-time "$out/$name-cycles-s$seed.exr")")
    done
  done
  t=$(printf '%s\n' "${t_times[@]}" | median)
  c=$(printf '%s\n' "${c_times[@]}" | median)
  # Both renderers are deterministic per seed, so the last round's images stand for all.
  nt=$(metrics noise "$out/$name-tessera-s1.exr" "$out/$name-tessera-s2.exr")
  nc=$(metrics noise "$out/$name-cycles-s1.exr" "$out/$name-cycles-s2.exr")
  rt=$(metrics noise --normalized "$out/$name-tessera-s1.exr" "$out/$name-tessera-s2.exr")
  rc=$(metrics noise --normalized "$out/$name-cycles-s1.exr" "$out/$name-cycles-s2.exr")
  pt=$(metrics noise --relative "$out/$name-tessera-s1.exr" "$out/$name-tessera-s2.exr")
  pc=$(metrics noise --relative "$out/$name-cycles-s1.exr" "$out/$name-cycles-s2.exr")
  ft=$(metrics noise --scale-free "$out/$name-tessera-s1.exr" "$out/$name-tessera-s2.exr")
  fc=$(metrics noise --scale-free "$out/$name-cycles-s1.exr" "$out/$name-cycles-s2.exr")
  # Cycles' render_time is given to 0.01 s: a render that short cannot be timed (n/a).
  awk -v n="$name" -v t="$t" -v c="$c" -v s="$samples" -v nt="$nt" -v nc="$nc" -v rt="$rt" -v rc="$rc" -v pt="$pt" -v pc="$pc" -v ft="$ft" -v fc="$fc" '
    function per(x, y, f) { return x > 0 && y > 0 ? sprintf(f, x / y) : "n/a" }
    BEGIN {
      printf "| %s | %.3f | %.2f | %s | %s | %.3e | %.3e | %.3e | %.3e | %s | %s | %s | %s |\n", n, t, c,
        per(s / 1e6, t, "%.3f"), per(s / 1e6, c, "%.3f"), nt, nc, t * nt, c * nc,
        per(c * nc, t * nt, "%.2fx"), per(c * rc, t * rt, "%.2fx"), per(c * pc, t * pt, "%.2fx"),
        per(c * fc, t * ft, "%.2fx") }'
  echo "$name: tessera ${t_times[*]} s; Cycles ${c_times[*]} s" >&2
  to_png "$out/$name-tessera-vs-cycles.png" "$out/$name-tessera-s1.exr" "$out/$name-cycles-s1.exr"
done
echo
world_name="white world"
[[ "${CWORLD:-1}" == 0 ]] && world_name="black world"
[[ -n "$envmap" ]] && world_name="world: $(basename "$envmap")"
echo "$width x $height, $spp spp, 8 bounces, 2 threads, $world_name, Cycles $([[ "${CUNBIASED:-0}" == 1 ]] && echo unbiased || echo "with its default clamps and glossy filter");" \
  "seeds 1 and 2, each renderer run $rounds times per seed, alternating; medians.${tessera_extra[*]:+ tessera options: ${tessera_extra[*]}.}"
echo "load after: $(uptime)" >&2
