// One pixel traced alone (tessera render --pixel): its samples taken as render_frame takes
// them (renderer/render/camera_sample.h), the first few with their paths recorded.
#pragma once

#include <vector>

#include "renderer/render/render.h"

namespace tessera {

struct PixelTraceParams {
  int x = 0, y = 0;  // in the frame, (0, 0) at the top left
  int recorded = 4;  // samples whose paths are kept
};

struct PixelTrace {
  std::vector<PathRecord> paths;  // samples 0 .. recorded - 1
  std::vector<vec3> radiance;  // of each recorded sample
  glm::dvec3 mean{0.0};  // over settings.spp samples: the value render_frame gives the pixel
  int samples = 0;
  std::uint64_t dropped = 0;  // non-finite samples, counted as black
};

PixelTrace trace_pixel(const RenderScene& scene, const RenderCamera& camera, const RenderSettings& settings,
                       const PixelTraceParams& params);

}  // namespace tessera
