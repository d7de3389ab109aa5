#include "renderer/render/pixel_trace.h"

#include <algorithm>

#include "renderer/render/camera_sample.h"
#include "renderer/render/frame_guide.h"

namespace tessera {

PixelTrace trace_pixel(const RenderScene& scene, const RenderCamera& camera, const RenderSettings& settings,
                       const PixelTraceParams& params) {
  CameraSampler sampler(scene, camera, settings);
  FrameGuide guide(scene, camera, settings);  // learnt from the whole frame, as render_frame's
  sampler.use_guide(guide.guide(), false);
  PixelTrace trace;
  const int recorded = std::clamp(params.recorded, 0, settings.spp);
  trace.paths.resize(recorded);
  trace.radiance.resize(recorded);
  PathCounters counters;
  glm::dvec3 sum(0.0);
  // Wave by wave, so that the samples go in the groups render_frame traces them in.
  for (const SampleWave& wave : sample_waves_of(settings)) {
    std::vector<PathRecord*> records;
    for (int s = wave.begin; s < wave.end; ++s) records.push_back(s < recorded ? &trace.paths[s] : nullptr);
    sampler.sample_span(params.x, params.y, wave.begin, wave.end, counters, [&](int s, const CameraSampleResult& r) {
      sum += glm::dvec3(r.radiance);  // an invalid sample is black, as on the film
      if (s < recorded) trace.radiance[s] = r.radiance;
    }, records.data());
    if (guide.learns_from(wave)) guide.learn_alone(wave), guide.finish_round(wave, nullptr);
  }
  trace.samples = settings.spp;
  trace.mean = sum / static_cast<double>(settings.spp);
  trace.dropped = counters.dropped;
  return trace;
}

}  // namespace tessera
