#!/usr/bin/env bash
# How close tessera's denoised low-spp frame comes to a converged reference, against plain
# renders: renders SCENE at a high spp with --aov albedo,normal (the reference, seed 1000,
# cached in OUT_DIR), then with seed SEED (1): SPP (16) spp noisy, SPP spp with --denoise (and
# --aov depth: the denoiser regresses on depth too when the frame has it), HIGH_SPP
# (256) spp noisy, and prints a Markdown table of each one's relative MSE against the
# reference, over the whole image and inside the edge mask (pixels where the reference's
# albedo or normal changes, dilated by one pixel: where a feature-guided denoiser blurs), with
# wall-clock and tessera's own render seconds. Writes into OUT_DIR: NAME-side-by-side.png
# (noisy | denoised | HIGH_SPP | reference), NAME-errors.png (their error maps, same order and
# log scale) and NAME-edges.png (the mask).
#   tools/denoise-quality.sh [--spp N] [--high-spp N] [--ref-spp N] [--seed S] [--width W] [--height H] [--threads T] [--envmap FILE] [--out DIR] [--fresh-ref] SCENE [-- TESSERA_OPTION...]
# TESSERA_OPTIONs go to every render, the reference included (e.g. -- --aperture 0.1047207
# --focus-distance 10). Without --height, the camera's aspect ratio decides it. Until the
# tessera binary has --denoise (TESSERA=path, default build/tessera), the denoised column is
# skipped, with a message. The reference is reused while the scene and options are the same;
# --fresh-ref renders it again (do so after a change to the renderer).
# shellcheck disable=SC2054  # commas inside option values (1,1,1; albedo,normal) are meant
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
tessera="${TESSERA:-$root/build/tessera}"
source "$root/tools/measure-lib.sh"
usage="usage: $0 [--spp N] [--high-spp N] [--ref-spp N] [--seed S] [--width W] [--height H] [--threads T] [--envmap FILE] [--out DIR] [--fresh-ref] SCENE [-- TESSERA_OPTION...]"
spp=16 high_spp=256 ref_spp=4096 seed=1 width=640 height="" threads=2 envmap="" out=/tmp/tessera-denoise-quality fresh=0
while [[ $# -gt 0 && "$1" == --?* ]]; do
  case "$1" in
    --spp) spp=$2; shift 2 ;;
    --high-spp) high_spp=$2; shift 2 ;;
    --ref-spp) ref_spp=$2; shift 2 ;;
    --seed) seed=$2; shift 2 ;;
    --width) width=$2; shift 2 ;;
    --height) height=$2; shift 2 ;;
    --threads) threads=$2; shift 2 ;;
    --envmap) envmap=$(realpath -e "$2"); shift 2 ;;
    --out) out=$2; shift 2 ;;
    --fresh-ref) fresh=1; shift ;;
    *) echo "unknown option $1; $usage" >&2; exit 2 ;;
  esac
done
[[ $# -ge 1 && "$1" != -- ]] || { echo "$usage" >&2; exit 2; }
scene=$1
shift
[[ $# -gt 0 ]] && { [[ "$1" == -- ]] || { echo "$usage" >&2; exit 2; }; shift; }
[[ -f "$scene" ]] || { echo "$scene: no such file" >&2; exit 2; }
tessera_extra=(--width "$width" --threads "$threads")
[[ -n "$height" ]] && tessera_extra+=(--height "$height")
[[ -n "$envmap" ]] && tessera_extra+=(--envmap "$envmap")
tessera_extra+=("$@")
mkdir -p "$out"
name=$(basename "${scene%.*}")
p="$out/$name"

# The reference, cached under a key of everything that changes its pixels.
key=$(printf '%s\n' "$(realpath "$scene")" "$ref_spp" "${tessera_extra[@]}" "$("$tessera" --version)" | md5sum | cut -c1-10)
ref="$p-ref-${ref_spp}spp-$key.exr"
if [[ $fresh == 1 || ! -s "$ref" ]]; then
  echo "rendering the reference, $ref_spp spp: $ref" >&2
  ref_wall=$(tessera_render "$ref" "$scene" --spp "$ref_spp" --seed 1000 --aov albedo,normal)
else
  ref_wall="(cached)"
  echo "using the cached reference $ref (--fresh-ref to render it again)" >&2
fi
edge_fraction=$(metrics edge-mask "$ref" -o "$p-edges.exr")
oiiotool "$p-edges.exr" --ch 0,0,0 --chnames R,G,B -d uint8 -o "$p-edges.png"

has_denoise=0
tessera_has --denoise && has_denoise=1
[[ $has_denoise == 1 ]] ||
  echo "NOTE: $tessera has no --denoise (tessera render --help): the denoised row is skipped" >&2

echo "| image | wall s | tessera render s | relMSE | relMSE in edges ($(awk -v f="$edge_fraction" 'BEGIN {printf "%.1f", 100 * f}')% of pixels) |"
echo "|---|---:|---:|---:|---:|"
row() {  # label wall-seconds image.exr
  printf '| %s | %s | %.3f | %.4e | %.4e |\n' "$1" "$2" "$(metrics render-time "$3")" \
    "$(metrics relmse "$3" "$ref")" "$(metrics relmse "$3" "$ref" --mask "$p-edges.exr")"
}
panels=() errors=()
for run in noisy denoised high; do
  case $run in
    noisy) img="$p-${spp}spp-s$seed.exr" label="$spp spp" opts=(--spp "$spp") ;;
    denoised) img="$p-${spp}spp-s$seed-denoised.exr" label="$spp spp, denoised" opts=(--spp "$spp" --denoise --aov albedo,normal,depth) ;;
    high) img="$p-${high_spp}spp-s$seed.exr" label="$high_spp spp" opts=(--spp "$high_spp") ;;
  esac
  if [[ $run == denoised && $has_denoise == 0 ]]; then
    echo "| $label | not in this build | | | |"
    continue
  fi
  wall=$(tessera_render "$img" "$scene" --seed "$seed" "${opts[@]}")
  row "$label" "$wall" "$img"
  metrics error-map "$img" "$ref" -o "$p-error-$run.png"
  panels+=("$img") errors+=("$p-error-$run.png")
  # The denoiser must have been given the same samples as the plain render of the same seed.
  if [[ $run == denoised ]] && d=$(metrics noise "$img" "${panels[0]}" --channels noisy.R,noisy.G,noisy.B --ref-channels R,G,B 2>/dev/null) &&
     [[ $d != 0.000000e+00 ]]; then
    echo "WARNING: the denoised render's noisy.* differ from the plain $spp spp render (mean sq. diff / 2 = $d)" >&2
  fi
done
printf '| reference, %s spp | %s | %.3f | 0 | 0 |\n' "$ref_spp" "$ref_wall" "$(metrics render-time "$ref")"
to_png "$p-side-by-side.png" "${panels[@]}" "$ref"
oiiotool "${errors[@]}" --mosaic "${#errors[@]}x1" -o "$p-errors.png"
echo
echo "$scene, $(iinfo "$ref" | sed -n 's/.*: *\([0-9]* x *[0-9]*\),.*/\1/p' | tr -d ' '), $threads threads," \
  "tessera options: ${tessera_extra[*]}; relMSE = mean((img - ref)^2 / (ref^2 + 0.01)) over RGB."
echo "Images: $p-side-by-side.png ($spp spp |$([[ $has_denoise == 1 ]] && echo " denoised |") $high_spp spp | reference), $p-errors.png, $p-edges.png" >&2
