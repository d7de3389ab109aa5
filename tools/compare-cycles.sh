#!/usr/bin/env bash
# Renders glTF scenes with tessera and with Blender Cycles at matched settings (uniform
# white world of radiance 1, 8 bounces, no adaptive sampling or denoising, 2 threads, same
# camera, size and samples), alternating A B A B, and prints a Markdown table of camera
# samples per second (median per renderer) and their ratio; each run's times go to stderr.
# Also writes, per scene, a PNG with the two images side by side into OUT_DIR.
#   tools/compare-cycles.sh [--spp N] [--width W] [--height H] [--rounds R] [--out DIR] SCENE...
# Needs: apt-get install blender python3-numpy openimageio-tools; a built build/tessera.
# Render time is each renderer's own (tessera: "render X s"; Cycles: render_time in its EXR
# header), without start-up, scene import or BVH build.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
tessera="${TESSERA:-$root/build/tessera}"
spp=16 width=640 height=360 rounds=2 out=/tmp/tessera-vs-cycles
while [[ $# -gt 0 && "$1" == --* ]]; do
  case "$1" in
    --spp) spp=$2; shift 2 ;;
    --width) width=$2; shift 2 ;;
    --height) height=$2; shift 2 ;;
    --rounds) rounds=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    *) echo "unknown option $1" >&2; exit 2 ;;
  esac
done
[[ $# -gt 0 ]] || { echo "usage: $0 [--spp N] [--width W] [--height H] [--rounds R] [--out DIR] SCENE..." >&2; exit 2; }
mkdir -p "$out"

median() { sort -g | awk '{a[NR]=$1} END {print (NR%2) ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2}'; }

tessera_seconds() {  # scene out.exr -> render seconds
  "$tessera" render "$1" -o "$2" --width "$width" --height "$height" --spp "$spp" --max-bounces 8 \
    --threads 2 --background 1,1,1 2>&1 | sed -n 's/.*render \([0-9.]*\) s$/\1/p'
}

cycles_seconds() {  # scene out.exr -> render seconds
  # A plain environment: Blender must not pick up a pyenv Python's standard library.
  env -i HOME="$HOME" PATH=/usr/bin:/bin blender -b --factory-startup -t 2 --python "$root/tools/peers/cycles_render.py" \
    -- "$1" "$2" "$spp" "$width" "$height" >"$out/cycles.log" 2>&1
  iinfo -v "$2" | sed -n 's/.*cycles.ViewLayer.render_time: "\([0-9]*\):\([0-9.]*\)".*/\1 \2/p' | awk '{print $1 * 60 + $2}'
}

samples=$((width * height * spp))
echo "| scene | tessera s (median) | Cycles s (median) | tessera M samples/s | Cycles M samples/s | tessera / Cycles |"
echo "|---|---:|---:|---:|---:|---:|"
for scene in "$@"; do
  name=$(basename "${scene%.*}")
  t_times=() c_times=()
  for ((r = 0; r < rounds; ++r)); do
    t_times+=("$(tessera_seconds "$scene" "$out/$name-tessera.exr")")
    c_times+=("$(cycles_seconds "$scene" "$out/$name-cycles.exr")")
  done
  t=$(printf '%s\n' "${t_times[@]}" | median)
  c=$(printf '%s\n' "${c_times[@]}" | median)
  awk -v n="$name" -v t="$t" -v c="$c" -v s="$samples" \
    'BEGIN {printf "| %s | %.2f | %.2f | %.3f | %.3f | %.2fx |\n", n, t, c, s / t / 1e6, s / c / 1e6, c / t}'
  echo "$name: tessera ${t_times[*]} s; Cycles ${c_times[*]} s" >&2
  # RGB only: tessera's EXR has an A channel and Cycles' has none, which would leave the
  # Cycles half transparent in the PNG.
  oiiotool "$out/$name-tessera.exr" --ch R,G,B --colorconvert linear sRGB \
    "$out/$name-cycles.exr" --ch R,G,B --colorconvert linear sRGB \
    --mosaic 2x1 -o "$out/$name-tessera-vs-cycles.png" 2>/dev/null || true
done
echo
echo "$width x $height, $spp spp, 8 bounces, 2 threads, white world; each renderer run $rounds times, alternating."
