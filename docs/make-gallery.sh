#!/usr/bin/env bash
# Renders every picture of docs/gallery.md into docs/images/gallery-*.png, with exactly the
# commands that docs/gallery.md prints beside each picture (run from the repository root).
#
#   docs/make-gallery.sh                          # uses build/tessera (./tessera builds it)
#   TESSERA=build-docs/tessera docs/make-gallery.sh
#
# The paper's scenes use the commands of scenes/paper/README.md with a smaller --width and
# --spp (the README's 1200 x 675 at 500 spp takes hours on 2 cores). Needs oiiotool (Debian
# 12: openimageio-tools) for the gamma-2 conversion and the difference image. Renders run one
# after the other, each on all cores; the time of each is printed. Intermediate EXRs go to a
# temporary directory that is deleted at the end. About 9 minutes on 2 shared cores
# (379 s measured before the material scenes, which took 150 s).
# shellcheck source=docs/prelude.sh
source "$(dirname "${BASH_SOURCE[0]}")/prelude.sh"
need_oiiotool

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p docs/images
start=$SECONDS
sky=scenes/paper/sky-gradient.hdr
env=scenes/env/spruit_sunrise_1k.hdr

# --- The paper's scenes (scenes/paper/README.md), lit by RTOW's sky ----------------------------
run tessera render scenes/paper/three-balls.gltf -o docs/images/gallery-three-balls.png \
    --envmap $sky --width 800 --spp 128 --max-bounces 50
run tessera render scenes/paper/three-balls.gltf -o docs/images/gallery-bounces-1.png \
    --envmap $sky --width 400 --spp 128 --max-bounces 1
run tessera render scenes/paper/three-balls.gltf -o docs/images/gallery-bounces-5.png \
    --envmap $sky --width 400 --spp 128 --max-bounces 5
run tessera render scenes/paper/refraction.gltf -o docs/images/gallery-refraction.png \
    --envmap $sky --width 800 --spp 128 --max-bounces 50

# The cover at the reference's size and samples (400 x 225, 32 spp), converted the book's way
# (clamp to [0, 0.999], gamma 2), and its difference from the reference x 3.
run tessera render scenes/paper/grid-of-spheres.gltf -o "$tmp/grid.exr" --envmap $sky \
    --width 400 --spp 32 --max-bounces 50 --aperture 0.1047207 --focus-distance 10
run oiiotool "$tmp/grid.exr" --ch R,G,B --clamp:min=0:max=0.999 --powc 0.5 -d uint8 -o docs/images/gallery-grid-of-spheres-400-gamma2.png
run oiiotool scenes/paper/seed/grid_of_spheres_reference_400x225.png docs/images/gallery-grid-of-spheres-400-gamma2.png \
    --absdiff --mulc 3 -d uint8 -o docs/images/gallery-grid-of-spheres-400-diff.png
# And larger, with more samples (sRGB, as --preview writes it).
run tessera render scenes/paper/grid-of-spheres.gltf -o docs/images/gallery-grid-of-spheres-800.png \
    --envmap $sky --width 800 --spp 128 --max-bounces 50 --aperture 0.1047207 --focus-distance 10

# --- Khronos sample models (automatic camera, looking down -Z) -------------------------------
run tessera render scenes/khronos/DamagedHelmet/glTF-Binary/DamagedHelmet.glb --envmap $env \
    --width 640 --spp 128 -o docs/images/gallery-damaged-helmet.png
run tessera render scenes/khronos/MetalRoughSpheresNoTextures/glTF-Binary/MetalRoughSpheresNoTextures.glb \
    --envmap $env --width 640 --spp 128 -o docs/images/gallery-metal-rough-spheres.png
run tessera render scenes/khronos/ClearCoatTest/glTF-Binary/ClearCoatTest.glb --envmap $env \
    --width 800 --height 600 --fov 24 --spp 64 -o docs/images/gallery-clearcoat-test.png
run tessera render scenes/khronos/AnisotropyRotationTest/glTF-Binary/AnisotropyRotationTest.glb --envmap $env \
    --width 800 --height 450 --spp 64 -o docs/images/gallery-anisotropy-rotation-test.png
run tessera render scenes/khronos/AnisotropyStrengthTest/glTF-Binary/AnisotropyStrengthTest.glb --envmap $env \
    --width 800 --height 600 --spp 64 -o docs/images/gallery-anisotropy-strength-test.png
# The glass tests under the default white background (no light in the files: 'auto' is a
# uniform white), and once under the sunrise, whose small sun reaches what is behind the glass
# only through caustics.
run tessera render scenes/khronos/TransmissionRoughnessTest/glTF-Binary/TransmissionRoughnessTest.glb \
    --width 800 --height 450 --fov 14 --spp 128 -o docs/images/gallery-transmission-roughness-test.png
run tessera render scenes/khronos/TransmissionRoughnessTest/glTF-Binary/TransmissionRoughnessTest.glb \
    --envmap $env --width 800 --height 450 --fov 14 --spp 128 -o docs/images/gallery-transmission-roughness-test-sunrise.png
run tessera render scenes/khronos/AttenuationTest/glTF-Binary/AttenuationTest.glb \
    --width 800 --height 600 --fov 22 --spp 128 -o docs/images/gallery-attenuation-test.png
run tessera render scenes/khronos/TextureTransformTest/glTF/TextureTransformTest.gltf \
    --width 480 --spp 64 -o docs/images/gallery-texture-transform-test.png
run tessera render scenes/khronos/VertexColorTest/glTF-Binary/VertexColorTest.glb \
    --width 480 --spp 64 -o docs/images/gallery-vertex-color-test.png

# --- tessera's own test scenes for the newest Khronos materials --------------------------------
run tessera render scenes/material-extensions/iridescence.gltf --width 800 --spp 128 \
    -o docs/images/gallery-iridescence.png
run tessera render scenes/material-extensions/dispersion.gltf --width 800 --spp 128 \
    -o docs/images/gallery-dispersion.png
run tessera render scenes/material-extensions/diffuse-transmission.gltf --width 800 --spp 64 \
    -o docs/images/gallery-diffuse-transmission.png
for variant in none red green; do
  run tessera render scenes/material-variants/material-variants.gltf --width 256 --spp 16 \
      $([[ $variant == none ]] || echo --variant $variant) -o docs/images/gallery-variant-$variant.png
done

# --- Animation: a skinned walk as a frame sequence, and motion blur -----------------------------
run tessera render scenes/khronos/CesiumMan/glTF-Binary/CesiumMan.glb --frames 0:42:6 \
    --width 200 --height 260 --spp 64 --background 0.8,0.85,0.9 -o "$tmp/walk.##.png"
run oiiotool "$tmp"/walk.{00,06,12,18,24,30,36,42}.png --mosaic 8x1 -o docs/images/gallery-cesium-walk.png
for shutter in none -0.5,0.5; do
  run tessera render scenes/khronos/BoxAnimated/glTF-Binary/BoxAnimated.glb --time 1.2 --fps 6 \
      $([[ $shutter == none ]] || echo --shutter $shutter) --width 400 --spp 128 -o "$tmp/box-$shutter.png"
done
run oiiotool "$tmp/box-none.png" "$tmp/box--0.5,0.5.png" --mosaic 2x1 -o docs/images/gallery-motion-blur-box.png
run tessera render scenes/khronos/CesiumMan/glTF-Binary/CesiumMan.glb --frame 20 --shutter -1,1 \
    --width 400 --height 520 --spp 256 --background 0.8,0.85,0.9 -o docs/images/gallery-motion-blur-walk.png

echo "make-gallery.sh: done in $((SECONDS - start)) s" >&2
ls -l docs/images/gallery-* >&2
