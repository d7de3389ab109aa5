# shellcheck shell=bash disable=SC2154,SC2054  # the caller sets root, tessera, out, tessera_extra; commas are oiiotool's
# Shared by tools/compare-cycles.sh and tools/denoise-quality.sh (sourced, not run): running
# tessera and Cycles once, reading their render times, medians, PNGs.
# The caller sets: root (the repository), tessera (the binary), out (a directory), and may set
# tessera_extra (an array of options added to every tessera render).

metrics() { /usr/bin/python3 "$root/tools/image_metrics.py" "$@"; }  # Debian's python: numpy, OpenImageIO

median() { sort -g | awk '{a[NR]=$1} END {print (NR%2) ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2}'; }

# Does this tessera binary have the option? (--denoise, --noise-threshold: added by other branches)
tessera_has() { "$tessera" render --help 2>/dev/null | grep -- "$1" >/dev/null; }  # not -q: an early exit would SIGPIPE tessera

# tessera_render OUT.exr SCENE OPTION...: renders, prints the wall seconds (process start to
# exit: start-up, loading, BVH, sampling, any denoising, writing). tessera's own sampling time
# is in the EXR header (metrics render-time). On failure, shows tessera's messages and stops.
tessera_render() {
  local exr=$1 scene=$2 t0 t1
  shift 2
  t0=$(date +%s.%N)
  if ! "$tessera" render "$scene" -o "$exr" -q "${tessera_extra[@]}" "$@" >"$out/tessera.log" 2>&1; then
    echo "tessera failed: $tessera render $scene -o $exr ${tessera_extra[*]} $*" >&2
    cat "$out/tessera.log" >&2
    exit 1
  fi
  t1=$(date +%s.%N)
  awk -v a="$t0" -v b="$t1" 'BEGIN {printf "%.3f\n", b - a}'
}

# cycles_render OUT.exr SCENE SPP WIDTH HEIGHT SEED [ENVMAP]: renders with Blender Cycles
# (tools/peers/cycles_render.py: 8 bounces, 2 threads, no adaptive sampling or denoising).
# A plain environment: Blender must not pick up a pyenv Python's standard library.
cycles_render() {
  local exr=$1 scene=$2
  shift 2
  if ! env -i HOME="$HOME" PATH=/usr/bin:/bin CUNBIASED="${CUNBIASED:-0}" CWORLD="${CWORLD:-1}" blender -b --factory-startup -t 2 \
      --python "$root/tools/peers/cycles_render.py" -- "$(realpath "$scene")" "$exr" "$@" >"$out/cycles.log" 2>&1 ||
     [[ ! -s "$exr" ]]; then
    echo "Cycles failed on $scene; its log:" >&2
    tail -20 "$out/cycles.log" >&2
    exit 1
  fi
}

# to_png OUT.png IMG.exr[:CHANNELS] ...: the images side by side, RGB (tessera's A channel would
# make Cycles' half transparent), linear to sRGB, no tone mapping.
to_png() {
  local png=$1 args=() n=0 f ch
  shift
  for f in "$@"; do
    ch=R,G,B
    [[ "$f" == *.exr:* ]] && { ch=${f##*.exr:}; f=${f%:"$ch"}; }
    # --chnames: a noisy.R,noisy.G,noisy.B subset must become R,G,B to be shown as colour.
    args+=("$f" --ch "$ch" --chnames R,G,B --colorconvert linear sRGB)
    n=$((n + 1))
  done
  oiiotool "${args[@]}" --mosaic "${n}x1" -o "$png"
}
