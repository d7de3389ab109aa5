// One camera sample of one pixel: the sampler for (pixel, sample, seed), the filter-sampled
// point, the lens and the time, the ray, the path. render_frame takes every sample this way
// and trace_pixel (--pixel) takes a pixel's the same way, so both see the same paths.
#pragma once

#include "renderer/camera.h"
#include "renderer/integrator/path_tracer.h"
#include "renderer/pixel_filter.h"
#include "renderer/render_scene.h"

namespace tessera {

struct RenderSettings;

struct CameraSampleResult {
  vec3 radiance{0.0f};
  FirstHit first;
  float depth = 0.0f;  // of the first hit, along the camera's view axis at the sample's time
  bool valid = true;  // false: the camera made no finite ray (the sample counts as black)
};

class CameraSampler {
 public:
  CameraSampler(const RenderScene& scene, const RenderCamera& camera, const RenderSettings& settings);
  // Sample `s` of pixel (fx, fy) of the frame (not of a crop: what the samples depend on).
  CameraSampleResult sample(int fx, int fy, int s, PathCounters& counters, PathRecord* record = nullptr) const;

 private:
  const RenderScene& scene_;
  const RenderCamera& camera_;
  const RenderSettings& settings_;
  PixelFilter filter_;
  PathTracerParams params_;
  vec3 forward_;
  bool camera_moves_, timed_, has_lens_;
  float inv_w_, inv_h_;
};

}  // namespace tessera
