// What Embree alone traces on a scene: the ceiling tessera's rays/s are measured against
// (issue "Close to the ceiling"). The same camera and image as a render, but paths of pure
// diffuse bounces (cosine-distributed about the geometric normal) with no shading, no light
// sampling, no shadow rays and no film: only closest-hit traversal through the scene's own
// Embree BVH (its alpha filters included) and the few instructions between two rays. Each
// bounce leaves its surface as the renderer's rays do (offset_ray_origin): a ray that starts
// closer to a surface visits more of the BVH's boxes around its origin, and a minimum
// distance instead would skip geometry the renderer must find.
// Camera rays that a render would not trace either (renderer/camera/camera_coverage.h: pixels whose
// rays provably miss everything) are skipped here too, so both trace the same kind of rays.
#pragma once

#include <cstdint>

#include "renderer/camera/camera.h"
#include "renderer/scene/render_scene.h"

namespace tessera {

struct TraversalCeilingParams {
  int width = 0, height = 0;
  int spp = 1;
  int max_bounces = 8;  // rays per camera sample: at most max_bounces + 1
  int threads = 0;  // 0: all cores
  std::uint32_t seed = 1;
  float filter_radius = 0.75f;  // the render's filter_reach (the coverage's margin): its default filter's
  bool cull_camera_rays = true;  // as RenderSettings::cull_camera_rays
};

struct TraversalCeilingResult {
  std::uint64_t rays = 0;
  double seconds = 0.0;
  std::uint64_t culled_camera_rays = 0;  // skipped: their pixels' rays cannot hit anything
};

TraversalCeilingResult trace_traversal_ceiling(const RenderScene& scene, const RenderCamera& camera,
                                               const TraversalCeilingParams& params);

}  // namespace tessera
