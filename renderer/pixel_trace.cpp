#include "renderer/pixel_trace.h"

#include "renderer/camera_sample.h"

namespace tessera {

PixelTrace trace_pixel(const RenderScene& scene, const RenderCamera& camera, const RenderSettings& settings,
                       const PixelTraceParams& params) {
  const CameraSampler sampler(scene, camera, settings);
  PixelTrace trace;
  PathCounters counters;
  glm::dvec3 sum(0.0);
  for (int s = 0; s < settings.spp; ++s) {
    PathRecord record;
    const bool keep = s < params.recorded;
    const CameraSampleResult r = sampler.sample(params.x, params.y, s, counters, keep ? &record : nullptr);
    sum += glm::dvec3(r.radiance);  // an invalid sample is black, as on the film
    if (keep) {
      trace.paths.push_back(std::move(record));
      trace.radiance.push_back(r.radiance);
    }
  }
  trace.samples = settings.spp;
  trace.mean = sum / static_cast<double>(settings.spp);
  trace.dropped = counters.dropped;
  return trace;
}

}  // namespace tessera
