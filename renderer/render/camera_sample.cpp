#include "renderer/render/camera_sample.h"

#include <optional>

#include "renderer/integrator/emitter_pick.h"
#include "renderer/render/render.h"

namespace tessera {

CameraSampler::CameraSampler(const RenderScene& scene, const RenderCamera& camera, const RenderSettings& settings)
    : scene_(scene), camera_(camera), settings_(settings), filter_(settings.filter), forward_(camera.forward()) {
  scene.check_camera(camera);
  params_.max_bounces = settings.max_bounces;
  params_.light_sampling = settings.light_sampling;
  // MIS alone may skip emitters where they hardly light the scene; one strategy alone may not.
  if (settings.light_sampling == LightSampling::Mis)
    params_.emitter_pick = settings.emitter_pick > 0.0f ? std::min(settings.emitter_pick, 1.0f)
                                                        : emitter_pick_probability(scene, camera);
  params_.light_tree = scene.light_tree.used(settings.light_tree);
  // One strategy alone has no MIS weight to keep; the tree serves light sampling only.
  params_.emitter_tree = settings.light_sampling != LightSampling::BsdfOnly &&
                         emitter_tree_used(scene, camera, settings.light_tree);
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
  if (settings.cull_camera_rays) {
    CameraCoverageParams cp;
    cp.full_width = window.cropped() ? window.full_width : settings.width;
    cp.full_height = window.cropped() ? window.full_height : settings.height;
    cp.x0 = window.x, cp.y0 = window.y, cp.width = settings.width, cp.height = settings.height;
    cp.filter_radius = filter_reach(settings.filter);
    coverage_ = CameraCoverage(camera, *scene.geometry, cp);
  }
  uniform_background_ = !scene.environment.has_image();
  in_step_ = scene.geometry->unique_triangles() >= kInStepFrom;
  PathCounters once;
  background_ = camera_ray_escaped(scene, params_, Ray{vec3(0.0f), vec3(0.0f, 0.0f, -1.0f)}, once);  // any ray, when uniform
  background_dropped_ = once.dropped > 0;
}

// A pixel whose rays cannot hit anything, under a uniform background: each sample is what
// camera_ray_escaped gives any ray, with no ray made (the camera is well formed: its rays are
// finite, as coverage_ checks).
void CameraSampler::background_alone(int n, PathCounters& counters, CameraSampleResult* out) const {
  const vec3& radiance = background_samples(n, counters);
  for (int k = 0; k < n; ++k) {
    out[k] = CameraSampleResult{};
    out[k].radiance = radiance;
  }
}

const vec3& CameraSampler::background_samples(int n, PathCounters& counters) const {
  if (background_dropped_) counters.dropped += static_cast<std::uint64_t>(n);
  return background_;
}

// The sample's point on the film (from the filter's draw `u`, the sampler's first), lens
// position and time, drawn in that order; RenderCamera::generate_rays makes the group's rays.
void CameraSampler::camera_sample_point(int fx, int fy, const vec2& u, Sampler& rng, vec2& film, vec2& lens,
                                        float& time) const {
  const vec2 at = filter_.sample(u);
  lens = has_lens_ ? rng.next2() : vec2(0.5f);
  time = timed_ ? rng.next() : 0.0f;
  film = {(fx + at.x) * inv_w_, (fy + at.y) * inv_h_};
}

// Of a first hit at `distance`: along the camera's view axis at the ray's time.
float CameraSampler::depth(const Ray& ray, float distance) const {
  const vec3 axis = camera_moves_ ? -vec3(camera_.camera_to_world_at(ray.time)[2]) : forward_;
  return distance * glm::dot(ray.direction, axis);
}

// The group's samples whose camera rays hit something, their paths traced in step.
void CameraSampler::trace_hits_in_step(int n, const int* lane, const Ray* rays, const ClosestHit* hits,
                                       Sampler* const* samplers, PathCounters& counters, CameraSampleResult* out) const {
  Ray traced[kGroup];
  ClosestHit known[kGroup];
  Sampler* rngs[kGroup] = {};
  FirstHit firsts[kGroup];
  vec3 radiance[kGroup];
  int which[kGroup], m = 0;
  for (int k = 0; k < n; ++k) {
    if (lane[k] < 0 || !hits[lane[k]].found) continue;
    traced[m] = rays[lane[k]];
    known[m] = hits[lane[k]];
    rngs[m] = samplers[k];
    which[m++] = k;
  }
  trace_paths_from(scene_, params_, m, traced, known, rngs, firsts, counters, radiance);
  for (int j = 0; j < m; ++j) {
    out[which[j]].radiance = radiance[j];
    out[which[j]].first = firsts[j];
  }
}

void CameraSampler::sample(int fx, int fy, int s0, int n, PathCounters& counters, CameraSampleResult* out,
                           PathRecord* const* records) const {
  const bool traced = records || coverage_.may_hit(fx, fy);  // else every ray sees the background
  if (!traced && uniform_background_) return background_alone(n, counters, out);
  std::optional<Sampler> rng[kGroup];
  Ray rays[kGroup];
  int lane[kGroup];  // sample k's ray in the packet; -1: the camera made no finite ray
  int lanes = 0;
  const std::uint64_t pixel_key = Sampler::pixel_key(settings_.sampler, fx, fy, settings_.seed);
  Sampler* samplers[kGroup];
  for (int k = 0; k < n; ++k) samplers[k] = &rng[k].emplace(settings_.sampler, pixel_key, s0 + k);
  vec2 u[kGroup], film[kGroup], lens[kGroup];
  float time[kGroup];
  Sampler::next2_of_pixel(samplers, n, u);
  for (int k = 0; k < n; ++k) camera_sample_point(fx, fy, u[k], *samplers[k], film[k], lens[k], time[k]);
  Ray camera_rays[kGroup];
  camera_.generate_rays(film, lens, time, n, camera_rays);
  for (int k = 0; k < n; ++k) {
    const Ray& ray = camera_rays[k];
    out[k] = CameraSampleResult{};
    lane[k] = is_finite(ray.origin) && is_finite(ray.direction) ? lanes : -1;  // Embree would abort
    if (lane[k] < 0) {                                                        // on a non-finite ray
      ++counters.dropped;
      out[k].valid = false;
      continue;
    }
    rays[lanes++] = ray;
  }
  ClosestHit hits[kGroup];
  if (traced) scene_.geometry->intersect_packet(rays, lanes, hits);
  for (int l = 0; l < lanes; ++l)
    if (hits[l].found) scene_.geometry->prefetch_triangle(hits[l].hit);
  for (int l = 0; l < lanes; ++l)
    if (hits[l].found) scene_.geometry->prefetch_corners(hits[l].hit);
  // Then every large texture the hits read (DamagedHelmet: five of 2048x2048), before the
  // first path is shaded: their cache misses overlap.
  if (scene_.materials.prefetches_textures())
    for (int l = 0; l < lanes; ++l)
      if (hits[l].found) {
        const HitRecord& h = hits[l].hit;
        scene_.materials.prefetch_textures(scene_.geometry->texture_corners(h).at(h.u, h.v));
      }
  const bool in_step = in_step_ && !records;  // a recorded path is traced alone
  if (in_step) trace_hits_in_step(n, lane, rays, hits, samplers, counters, out);
  for (int k = 0; k < n; ++k) {
    if (lane[k] < 0) continue;
    const Ray& ray = rays[lane[k]];
    CameraSampleResult& r = out[k];
    PathRecord* record = records ? records[k] : nullptr;
    if (hits[lane[k]].found && in_step) {
      // traced above
    } else if (hits[lane[k]].found || record) {
      r.radiance = trace_path_from(scene_, params_, ray, &hits[lane[k]], *rng[k], r.first, counters, record);
    } else if (traced) {
      r.radiance = camera_ray_escaped(scene_, params_, ray, counters);
    } else {
      PathCounters untraced;  // of a ray not traced, only a dropped sample counts
      r.radiance = camera_ray_escaped(scene_, params_, ray, untraced);
      counters.dropped += untraced.dropped;
    }
    r.depth = depth(ray, r.first.distance);
  }
}

}  // namespace tessera
