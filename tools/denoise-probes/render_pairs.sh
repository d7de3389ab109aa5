#!/usr/bin/env bash
# Training pairs for the learned-denoiser probe: per view, an input at 16 spp (--denoise --aov depth:
# the noisy beauty, tessera's denoised image, the features and the half buffers) and a target at
# 64 spp of another seed (Noise2Noise: a noisy target of independent noise is an unbiased target for
# an L2 loss). Views: 24 random covers (make_training_scenes.py, seeds 101-124) from random
# cameras (each with depth of field at odds of 3 in 5, and under the paper's sky at odds of 3 in
# 5, else under the sunrise, turned); Khronos models, the paper's other scenes and the
# material-extension scenes under their default cameras.
#   render_pairs.sh OUT_DIR   (TESSERA: the binary, default build/tessera; about 20 minutes)
set -u
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
T=${TESSERA:-$root/build/tessera}
OUT=$1; mkdir -p "$OUT/scenes"
/usr/bin/python3 "$root/tools/denoise-probes/make_training_scenes.py" "$OUT/scenes" 101 125 > /dev/null
n=0
render_pair() {  # name scene opts...
  local name=$1 scene=$2; shift 2
  [[ -s $OUT/$name-target.exr ]] && return
  $T render "$scene" --spp 16 --seed $((n+7)) --denoise --aov depth -o $OUT/$name-input.exr --threads 2 "$@" > /dev/null 2>>$OUT/err.log || { echo "FAIL $name" >> $OUT/err.log; return; }
  $T render "$scene" --spp 64 --seed $((n+5007)) -o $OUT/$name-target.exr --threads 2 "$@" > /dev/null 2>>$OUT/err.log
  echo "$name $(date +%T)"
}
rnd() { /usr/bin/python3 -c "import random,sys; random.seed($1); print(' '.join('%.4f' % random.uniform(a,b) for a,b in zip(*[iter(map(float,sys.argv[1:]))]*2)))" "${@:2}"; }
for s in $(seq 101 124); do
  n=$s
  read az d h tx ty tz fov ap env rot <<< "$(rnd $s 0 6.283 7 16 0.8 3.5 -2 2 0 0.8 -2 2 18 40 0 1 0 1 0 360)"
  opts=$(/usr/bin/python3 -c "
import math; az,d,h,tx,ty,tz,fov,ap,env,rot=$az,$d,$h,$tx,$ty,$tz,$fov,$ap,$env,$rot
px,pz=tx+d*math.cos(az),tz+d*math.sin(az)
o='--camera-position %.3f,%.3f,%.3f --camera-target %.3f,%.3f,%.3f --fov %.2f'%(px,h,pz,tx,ty,tz,fov)
if ap>0.4: o+=' --aperture %.4f --focus-distance %.3f'%(0.03+0.15*(ap-0.4)/0.6, math.dist((px,h,pz),(tx,ty,tz)))
o+=' --envmap $root/scenes/paper/sky-gradient.hdr' if env<0.6 else ' --envmap $root/scenes/env/spruit_sunrise_1k.hdr --envmap-rotate %.0f'%rot
print(o)")
  render_pair cover-$s $OUT/scenes/cover-$s.gltf --width 640 --height 360 $opts
done
K=$root/scenes/khronos; P=$root/scenes/paper; E=$root/scenes/env/spruit_sunrise_1k.hdr; S=$P/sky-gradient.hdr
n=300; for sc in MetalRoughSpheresNoTextures TransmissionRoughnessTest ClearCoatTest AttenuationTest BoxTextured TextureSettingsTest CesiumMan AnisotropyStrengthTest; do
  f=$(ls $K/$sc/glTF/*.gltf 2>/dev/null | head -1); [[ -z $f ]] && f=$(ls $K/$sc/glTF-Binary/*.glb | head -1)
  n=$((n+1)); render_pair k-$sc $f --width 512 --envmap $E --envmap-rotate $((n*47 % 360))
done
n=400; render_pair p-three-balls $P/three-balls.gltf --width 640 --envmap $S
n=401; render_pair p-refraction $P/refraction.gltf --width 640 --envmap $S
n=402; render_pair p-timing $P/timing-scene.gltf --width 640 --envmap $S --aperture 0.1047207 --focus-distance 10
n=403; render_pair p-adversarial $P/adversarial.gltf --width 640 --envmap $S
for f in $root/scenes/material-extensions/*.gltf; do n=$((n+1)); render_pair m-$(basename $f .gltf) $f --width 512 --envmap $E; done
echo ALLDONE
