#!/usr/bin/env bash
# Renders the ten-scene A/B set with two tessera builds and compares each pair of images
# exactly (every channel, every pixel: idiff -fail 0 -warn 0). For a change meant to keep the
# images: PASS on all ten, or the first pixel that differs and how many do. Each scene
# covers a part of the renderer: area lights (the Cornell box), textures, normal maps and an
# environment image (DamagedHelmet), a million triangles of GGX (MetalRoughSpheres), and one
# scene per material extension.
#   tools/ab-images.sh /tmp/old/tessera build/tessera
# Needs: apt-get install openimageio-tools (idiff).
set -euo pipefail
[[ $# -eq 2 ]] || { echo "usage: $0 BASE_TESSERA NEW_TESSERA" >&2; exit 2; }
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
base=$1 new=$2
k=$root/scenes/khronos
size="--width 160 --height 90 --spp 16"
scenes=(
  "cornell|$root/scenes/cornell-box/cornell-box.gltf --width 160 --spp 16"
  "helmet|$k/DamagedHelmet/glTF-Binary/DamagedHelmet.glb --envmap $root/scenes/env/spruit_sunrise_1k.hdr $size"
  "spheres|$k/MetalRoughSpheresNoTextures/glTF-Binary/MetalRoughSpheresNoTextures.glb $size"
  "iridescence|$root/scenes/material-extensions/iridescence.gltf $size"
  "dispersion|$root/scenes/material-extensions/dispersion.gltf $size"
  "diffuse-transmission|$root/scenes/material-extensions/diffuse-transmission.gltf $size"
  "clearcoat|$k/ClearCoatTest/glTF-Binary/ClearCoatTest.glb $size"
  "transmission-roughness|$k/TransmissionRoughnessTest/glTF-Binary/TransmissionRoughnessTest.glb $size"
  "anisotropy|$k/AnisotropyRotationTest/glTF-Binary/AnisotropyRotationTest.glb $size"
  "three-balls|$root/scenes/paper/three-balls.gltf $size"
)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
failed=0
for entry in "${scenes[@]}"; do
  name=${entry%%|*}
  read -r -a args <<<"${entry#*|}"
  "$base" render "${args[@]}" -q -o "$out/$name-base.exr"
  "$new" render "${args[@]}" -q -o "$out/$name-new.exr"
  if verdict=$(idiff -a -fail 0 -failpercent 0 -warn 0 "$out/$name-base.exr" "$out/$name-new.exr" 2>&1); then
    echo "$name PASS"
  else
    failed=1
    echo "$name: $(grep -E 'Max error|pixels' <<<"$verdict" | head -2 | tr -s ' ' | paste -sd ';')"
  fi
done
exit $failed
