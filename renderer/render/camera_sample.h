// Camera samples of one pixel: for each, the sampler for (pixel, sample, seed), the
// filter-sampled point, the lens and the time, the ray, the path. Consecutive samples of the
// pixel go together: their camera rays are traced as one Embree packet (coherent rays: one
// traversal serves them all), then each path goes on alone from its first hit. A sample's
// first hit is the one a ray traced alone gets, but for ties between overlapping triangles
// (SceneGeometry::intersect_packet), which go the same way for the same group.
// render_frame takes every sample this way and trace_pixel (--pixel) takes a pixel's the same
// way, in the same groups, so both see the same paths.
#pragma once

#include <algorithm>

#include "renderer/camera/camera.h"
#include "renderer/camera/camera_coverage.h"
#include "renderer/integrator/path_tracer.h"
#include "renderer/camera/pixel_filter.h"
#include "renderer/scene/render_scene.h"

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
  static constexpr int kGroup = SceneGeometry::kPacketSize;
  static_assert(kGroup <= Sampler::kTogether);
  // Samples s0 .. s0 + n - 1 (n <= kGroup) of pixel (fx, fy) of the frame (not of a crop: what
  // the samples depend on) into out[0 .. n - 1]; records[k] (when given and not null) receives
  // sample s0 + k's path.
  void sample(int fx, int fy, int s0, int n, PathCounters& counters, CameraSampleResult* out,
              PathRecord* const* records = nullptr) const;
  // Samples begin .. end - 1 of the pixel in groups of kGroup from `begin`, as render_frame
  // takes those a pixel needs in one sample wave: each(s, result) in sample order. records:
  // as above, records[s - begin] for sample s.
  // Whether every camera sample of frame pixel (fx, fy) is the uniform background with no ray
  // made (its rays cannot hit anything, renderer/camera/camera_coverage.h): then each sample's result
  // is the radiance background_samples() gives (valid, no hit), and the caller may sum them
  // in closed form.
  bool background_only(int fx, int fy) const { return uniform_background_ && !coverage_.may_hit(fx, fy); }
  // The probability that a path vertex samples an emitter (integrator/emitter_pick.h).
  float emitter_pick() const { return params_.emitter_pick; }
  bool samples_light_tree() const { return params_.light_tree; }  // one punctual light per vertex
  // Paths guided by `guide` (null: not guided) from the next sample on, recording what they
  // find into it when `learn`.
  void use_guide(PathGuide* guide, bool learn) {
    params_.guide = guide;
    params_.learn = guide && learn;
  }
  bool samples_emitter_tree() const { return params_.emitter_tree; }  // emissive triangles chosen by the tree
  // n such samples: their radiance, each the same; counted as dropped when it is not finite.
  const vec3& background_samples(int n, PathCounters& counters) const;
  template <typename Each>
  void sample_span(int fx, int fy, int begin, int end, PathCounters& counters, Each&& each,
                   PathRecord* const* records = nullptr) const {
    CameraSampleResult r[kGroup];
    for (int s = begin; s < end; s += kGroup) {
      const int n = std::min(kGroup, end - s);
      sample(fx, fy, s, n, counters, r, records ? records + (s - begin) : nullptr);
      for (int k = 0; k < n; ++k) each(s + k, r[k]);
    }
  }

 private:
  void camera_sample_point(int fx, int fy, const vec2& u, Sampler& rng, vec2& film, vec2& lens, float& time) const;
  float depth(const Ray& ray, float distance) const;
  void background_alone(int n, PathCounters& counters, CameraSampleResult* out) const;
  void trace_hits_in_step(int n, const int* lane, const Ray* rays, const ClosestHit* hits, Sampler* const* samplers,
                          PathCounters& counters, CameraSampleResult* out) const;
  // A group's paths are traced in step (trace_paths_from) on meshes of this many triangles or
  // more, whose hits miss the caches: MetalRoughSpheresNoTextures (1 M) 5% faster; on smaller
  // ones the misses are few and stepping costs (DamagedHelmet, 15,000: 3% slower).
  static constexpr std::uint64_t kInStepFrom = 200'000;
  bool in_step_ = false;

  const RenderScene& scene_;
  const RenderCamera& camera_;
  const RenderSettings& settings_;
  PixelFilter filter_;
  PathTracerParams params_;
  vec3 forward_;
  bool camera_moves_, timed_, has_lens_;
  float inv_w_, inv_h_;
  // Pixels whose camera rays cannot hit anything (camera_coverage.h) see the background: their
  // rays are not traced, and under a uniform background not even made.
  CameraCoverage coverage_;
  bool uniform_background_;
  vec3 background_;  // what camera_ray_escaped returns there
  bool background_dropped_;  // it is not finite: each such sample is dropped
};

}  // namespace tessera
