#include "renderer/camera_sample.h"

#include "renderer/render.h"

namespace tessera {

CameraSampler::CameraSampler(const RenderScene& scene, const RenderCamera& camera, const RenderSettings& settings)
    : scene_(scene), camera_(camera), settings_(settings), filter_(settings.filter), forward_(camera.forward()) {
  params_.max_bounces = settings.max_bounces;
  params_.light_sampling = settings.light_sampling;
  params_.clamp = settings.clamp;
  params_.transparent_background = settings.aovs.coverage;
  // Motion blur: each camera sample draws its time, after the film and lens positions. A
  // scene where nothing moves draws none, so its numbers and image stay what they were.
  camera_moves_ = camera.moves();
  timed_ = scene.moves() || camera_moves_;
  has_lens_ = camera.lens_radius > 0.0f;  // a pinhole draws no lens position
  const FrameWindow& window = settings.window;
  inv_w_ = 1.0f / (window.cropped() ? window.full_width : settings.width);
  inv_h_ = 1.0f / (window.cropped() ? window.full_height : settings.height);
}

CameraSampleResult CameraSampler::sample(int fx, int fy, int s, PathCounters& counters, PathRecord* record) const {
  Sampler rng(settings_.sampler, fx, fy, s, settings_.seed);
  const vec2 at = filter_.sample(rng.next2());
  const vec2 lens = has_lens_ ? rng.next2() : vec2(0.5f);
  const float time = timed_ ? rng.next() : 0.0f;
  const Ray ray = camera_.generate_ray({(fx + at.x) * inv_w_, (fy + at.y) * inv_h_}, lens, time);
  CameraSampleResult r;
  if (!is_finite(ray.origin) || !is_finite(ray.direction)) {  // a degenerate camera: Embree
    ++counters.dropped;                                       // would abort on such a ray
    r.valid = false;
    return r;
  }
  r.radiance = trace_path(scene_, params_, ray, rng, r.first, counters, record);
  const vec3 axis = camera_moves_ ? -vec3(camera_.camera_to_world_at(time)[2]) : forward_;
  r.depth = r.first.distance * glm::dot(ray.direction, axis);
  return r;
}

}  // namespace tessera
