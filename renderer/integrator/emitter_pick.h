// How often a path vertex samples an emitter. Light sampling of the emissive triangles is one
// strategy of two (BSDF sampling finds them too, MIS weighs the two): a vertex takes it with
// probability q and skips it otherwise, its estimate divided by q and the emitters' MIS pdf
// multiplied by q, so any q > 0 gives the same image in expectation. q = 1 where the emitters
// are the only light (a black background: the default for scenes they light). Under a
// background or an environment the emitters compete with, q follows their share of the direct
// light on what the camera sees, estimated once per render from a grid of camera rays (a pilot,
// as variance-aware MIS sets its sample counts from one: Grittmann et al. 2019): DamagedHelmet's
// 15,452 emissive triangles give it almost none of its light under a white sky, and sampling one
// at every vertex cost 7% of its render for no measurable difference in noise.
#pragma once

#include "renderer/camera/camera.h"
#include "renderer/scene/render_scene.h"

namespace tessera {

struct EmitterPickParams {
  int grid = 32;  // camera rays per side of the image
  int directions = 4;  // emitter samples and background directions per camera hit
  // Emitters giving this share of the direct light or more are sampled at every vertex, below
  // it in proportion: a small bright emitter is what BSDF sampling finds worst, a sky the best
  // (the Cornell box under a white sky: its lamp gives 20% and wants q of 0.5 to 1).
  float full_share = 0.25f;
  float floor = 0.05f;  // the least q
  float time = 0.0f;  // the pilot looks at the scene at this shutter time
};

// q in [params.floor, 1]; exactly 1 where nothing competes with the emitters or there are none.
// A function of the scene and camera alone (its rays and random numbers fixed, summed in order):
// the same for every thread count, tile, rank and resume.
float emitter_pick_probability(const RenderScene& scene, const RenderCamera& camera, const EmitterPickParams& params = {});

// Which way a vertex chooses its emissive triangle under LightTreeUse::Auto: by the light tree
// (AreaLights::tree) where that cuts the variance of the light samples enough to pay for its
// walk, else by power. Measured by a pilot like the one above: at a grid of camera hits, light
// samples of the emitters' direct light (with visibility, materials left out), the same numbers
// choosing by power and by the tree; the tree when the power choice's variance, summed over the
// hits, is `gain` times the tree's or more. Many emitters spread over a hall gain 10x and more;
// a few, or emitters on one small object seen from near (DamagedHelmet's), about 1x or less,
// where the walk's cost (about a light sample's) is a loss.
struct EmitterTreeParams {
  int grid = 16;  // camera rays per side of the image
  int directions = 8;  // light samples per camera hit and way of choosing
  float gain = 2.0f;
  float time = 0.0f;
};
// On: the tree (when there is one); Off: by power; Auto: the pilot's choice. Deterministic as
// emitter_pick_probability is.
bool emitter_tree_used(const RenderScene& scene, const RenderCamera& camera, LightTreeUse use,
                       const EmitterTreeParams& params = {});
// The pilot's ratio, the power choice's variance over the tree's (infinite where only the
// tree's is 0; 1 where both are).
double emitter_tree_gain(const RenderScene& scene, const RenderCamera& camera, const EmitterTreeParams& params = {});

}  // namespace tessera
