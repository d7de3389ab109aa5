#!/usr/bin/env bash
# Renders every example image shown in docs/usage.md into docs/images/, with exactly the
# commands that docs/usage.md prints beside each image (run from the repository root).
#
#   docs/make-images.sh                          # uses build/tessera (./tessera builds it)
#   TESSERA=build-docs/tessera docs/make-images.sh
#
# Needs oiiotool (Debian 12: openimageio-tools, in third_party_config/debian-packages.txt)
# to turn the EXR's AOV layers into PNGs. About 3 to 6 minutes on 2 cores (198 s measured); renders run one after
# the other, each on all cores. The intermediate files, helmet.exr and cornell-box.exr, are deleted at the end.
# shellcheck source=docs/prelude.sh
source "$(dirname "${BASH_SOURCE[0]}")/prelude.sh"
need_oiiotool

mkdir -p docs/images
trap 'rm -f helmet.exr cornell-box.exr' EXIT
start=$SECONDS

# --- The architecture picture (docs/architecture.md), when Graphviz is installed ---------------
if command -v dot >/dev/null 2>&1; then
  run dot -Tpng -Gdpi=90 docs/images/architecture.dot -o docs/images/architecture.png
fi

# --- The default scene -----------------------------------------------------------------------
run tessera render scenes/cornell-box/cornell-box.gltf --width 640 --spp 512 -o docs/images/cornell-box.png
# README.md's image: exactly the command README.md gives first, its preview moved here.
run tessera render scenes/cornell-box/cornell-box.gltf --width 640 --spp 32 --denoise -o cornell-box.exr --preview cornell-box.png
run mv cornell-box.png docs/images/readme-cornell-box.png

# --- DamagedHelmet: automatic camera, 'auto' background, environment map, AOVs ------------
run tessera render scenes/khronos/DamagedHelmet/glTF-Binary/DamagedHelmet.glb --width 640 --spp 64 --background 0 -o docs/images/helmet-no-envmap.png
run tessera render scenes/khronos/DamagedHelmet/glTF-Binary/DamagedHelmet.glb --width 640 --spp 128 --envmap scenes/env/spruit_sunrise_1k.hdr --aov albedo,normal,depth -o helmet.exr --preview docs/images/helmet-envmap.png
run tessera render scenes/khronos/DamagedHelmet/glTF-Binary/DamagedHelmet.glb --width 640 --spp 128 --envmap scenes/env/spruit_sunrise_1k.hdr --envmap-rotate 180 -o docs/images/helmet-envmap-rotate-180.png
run oiiotool helmet.exr --ch R=Albedo.R,G=Albedo.G,B=Albedo.B --colorconvert linear sRGB -d uint8 -o docs/images/aov-albedo.png
run oiiotool helmet.exr --ch R=N.X,G=N.Y,B=N.Z --mulc 0.5 --addc 0.5 -d uint8 -o docs/images/aov-normal.png
run oiiotool helmet.exr --ch Z --dup --mulc 1e9 --clamp:min=0:max=1 --swap --subc 8.4 --mulc -0.7143 --clamp:min=0:max=1 --mul -d uint8 -o docs/images/aov-depth.png

# --- The Python package's dataset example (docs/python.md) ---------------------------------
run env PYTHONPATH=build/python python3 python/examples/render_dataset.py \
    scenes/khronos/DamagedHelmet/glTF-Binary/DamagedHelmet.glb /tmp/helmet-views --views 8 --size 256 --spp 16
run env PYTHONPATH=build/python python3 docs/python-dataset-sheet.py /tmp/helmet-views /tmp/helmet-views/sheet.exr 0 2 4 6
run oiiotool /tmp/helmet-views/sheet.exr --resize 50% -d uint8 -o docs/images/python-dataset.png

# --- Thin lens: the same box, focused by the image centre and at 0.95 m -------------------
run tessera render scenes/cornell-box/cornell-box.gltf --width 400 --spp 128 --aperture 0.1 -o docs/images/dof-autofocus.png
run tessera render scenes/cornell-box/cornell-box.gltf --width 400 --spp 128 --aperture 0.1 --focus-distance 0.95 -o docs/images/dof-focus-0.95.png

# --- Exposure: one radiance image, three display encodings --------------------------------
run tessera render scenes/cornell-box/cornell-box.gltf --width 320 --spp 64 --exposure -1 -o docs/images/exposure-minus-1.png
run tessera render scenes/cornell-box/cornell-box.gltf --width 320 --spp 64 --exposure 0 -o docs/images/exposure-0.png
run tessera render scenes/cornell-box/cornell-box.gltf --width 320 --spp 64 --exposure 1 -o docs/images/exposure-plus-1.png

# --- Perspective and orthographic glTF cameras ---------------------------------------------
run tessera render scenes/khronos/Cameras/glTF/Cameras.gltf --camera 0 --width 320 --spp 128 --envmap scenes/env/spruit_sunrise_1k.hdr -o docs/images/camera-0-perspective.png
run tessera render scenes/khronos/Cameras/glTF/Cameras.gltf --camera 1 --width 320 --spp 128 --envmap scenes/env/spruit_sunrise_1k.hdr -o docs/images/camera-1-orthographic.png

# --- Khronos sample models: what loads ------------------------------------------------------
run tessera render scenes/khronos/VertexColorTest/glTF-Binary/VertexColorTest.glb --width 480 --spp 64 -o docs/images/vertex-color-test.png
run tessera render scenes/khronos/TextureSettingsTest/glTF-Binary/TextureSettingsTest.glb --width 480 --spp 64 -o docs/images/texture-settings-test.png
run tessera render scenes/khronos/NegativeScaleTest/glTF-Binary/NegativeScaleTest.glb --width 480 --spp 64 -o docs/images/negative-scale-test.png
run tessera render scenes/khronos/OrientationTest/glTF-Binary/OrientationTest.glb --width 480 --spp 64 --envmap scenes/env/spruit_sunrise_1k.hdr -o docs/images/orientation-test.png
run tessera render scenes/khronos/MetalRoughSpheresNoTextures/glTF-Binary/MetalRoughSpheresNoTextures.glb --width 480 --spp 64 --envmap scenes/env/spruit_sunrise_1k.hdr -o docs/images/metal-rough-spheres.png

echo "make-images.sh: done in $((SECONDS - start)) s" >&2
ls -l docs/images >&2
