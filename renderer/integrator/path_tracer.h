// Unidirectional path tracing: BSDF sampling, next-event estimation for punctual lights,
// emission and the environment where paths end, Russian roulette.
#pragma once

#include <cstdint>

#include "renderer/ray.h"
#include "renderer/render_scene.h"
#include "renderer/sampler.h"

namespace tessera {

// How light from emitters and the environment is found. Mis is the renderer; the other two
// are single strategies kept to show, in tests and on request, that all three agree.
enum class LightSampling : std::uint8_t { Mis, BsdfOnly, LightsOnly };

struct PathTracerParams {
  int max_bounces = 8;  // scattering events; 0 shows emitters and the environment only
  int roulette_start = 3;  // bounces before Russian roulette may end a path
  LightSampling light_sampling = LightSampling::Mis;
  float clamp = 0.0f;  // > 0: clamp each sample's radiance to this luminance (biased; off by default)
  // A camera ray that hits nothing adds no background (it still lights what rays reach):
  // the film's alpha says where the background shows, for compositing over a plate.
  bool transparent_background = false;
};

// What the camera ray saw first, for the albedo, normal and depth outputs; through a mirror,
// the albedo and normal of what it shows (path_tracer.cpp: features_look_through).
struct FirstHit {
  bool hit = false;
  vec3 albedo{0.0f}, normal{0.0f};
  float distance = 0.0f;
};

struct PathCounters {
  std::uint64_t rays = 0;  // closest-hit and shadow rays traced
  std::uint64_t dropped = 0;  // samples dropped for a non-finite value
};

// Radiance arriving along `ray`, every ray of the path at ray.time. Never returns a
// non-finite value: such a sample is counted in counters.dropped and returns zero.
vec3 trace_path(const RenderScene& scene, const PathTracerParams& params, Ray ray,
                Sampler& rng, FirstHit& first, PathCounters& counters);

}  // namespace tessera
