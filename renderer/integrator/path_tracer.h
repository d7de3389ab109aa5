// Unidirectional path tracing: BSDF sampling, next-event estimation for punctual lights,
// emission and the environment where paths end, Russian roulette.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "renderer/guiding/path_guide.h"
#include "renderer/util/ray.h"
#include "renderer/scene/render_scene.h"
#include "renderer/sampling/sampler.h"

namespace tessera {

// How light from emitters and the environment is found. Mis is the renderer; the other two
// are single strategies kept to show, in tests and on request, that all three agree.
enum class LightSampling : std::uint8_t { Mis, BsdfOnly, LightsOnly };

struct PathTracerParams {
  int max_bounces = 8;  // scattering events; 0 shows emitters and the environment only
  int roulette_start = 5;  // bounces before Russian roulette may end a path
  LightSampling light_sampling = LightSampling::Mis;
  // The probability that a vertex samples an emitter (integrator/emitter_pick.h), in (0, 1].
  float emitter_pick = 1.0f;
  // Each vertex samples one point or spot light from the scene's LightTree (divided by the
  // probability of choosing it) instead of every one; directional lights are sampled each.
  bool light_tree = false;
  // Path guiding (renderer/guiding/path_guide.h): directions drawn in part from what the guide
  // learnt (integrator/guided_scattering.h); null: from the BSDF alone. `learn`: the paths
  // also record what they find into it (the guide must not be sampled from meanwhile by
  // anything that finishes its round).
  PathGuide* guide = nullptr;
  bool learn = false;
  // The emissive triangle a vertex samples is chosen by the area lights' light tree from the
  // vertex's position and normal (AreaLights::tree), instead of by power alone.
  bool emitter_tree = false;
  float clamp = 0.0f;  // > 0: clamp each sample's radiance to this luminance (biased; off by default)
  // A camera ray that hits nothing adds no background (it still lights what rays reach):
  // the film's alpha says where the background shows, for compositing over a plate.
  bool transparent_background = false;
};

// What reaches `origin` from `distance` along the unit direction wi (infinity: the
// environment) at `time`: 0 behind an opaque surface, what thin transmissive ones let through.
vec3 visibility(const RenderScene& scene, const vec3& origin, const vec3& wi, float distance, float time);
// What reaches `from` along wi from the point `on` of a surface of normal `normal` (a light's),
// `from` moved off its own surface. The ray from the moved origin meets that surface's plane
// (offset * cos between the normals / cos at the far end) before the point: it stops short of
// where it meets the plane, not of the point's distance. The offset grows with the
// coordinates, and far from the scene's origin (at y = 100: 2e-3) it exceeds any tolerance
// relative to the distance: the ray would be stopped by the light itself.
vec3 visibility_to_surface(const RenderScene& scene, const vec3& from, const vec3& wi, const vec3& on, const vec3& normal,
                           float time);

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

// A path as it was traced (--pixel prints it): each surface it met, and what each added to
// the sample's radiance (already multiplied by the throughput).
struct PathVertex {
  vec3 position{0.0f}, normal{0.0f};  // the shading normal, towards the arriving ray
  int material = -1;  // index into the scene's materials
  vec3 throughput{1.0f};  // the path's weight arriving here
  vec3 emitted{0.0f};  // emission seen here (MIS-weighted); an unlit surface's colour
  vec3 direct{0.0f};  // light sampled from here: punctual lights, emitters, the environment
  std::string lobe;  // the BSDF lobe sampled to leave ("diffuse", ...; "straight pass"); empty: ended
  float pdf = 0.0f;  // of the sampled direction, per solid angle (a straight pass: its probability)
};
struct PathRecord {
  std::vector<PathVertex> vertices;
  vec3 escaped{0.0f};  // the background or environment reached on leaving the scene
  std::string end;  // why the path ended ("left the scene", "max bounces", ...)
};

// Radiance arriving along `ray`, every ray of the path at ray.time. Never returns a
// non-finite value: such a sample is counted in counters.dropped and returns zero. `record`
// (null when rendering) receives the path's vertices; the radiance is the same either way.
vec3 trace_path(const RenderScene& scene, const PathTracerParams& params, Ray ray,
                Sampler& rng, FirstHit& first, PathCounters& counters, PathRecord* record = nullptr);
// The same path when the ray's closest hit is already known (`known`, as
// SceneGeometry::intersect gives it: camera rays traced as a packet); null: not known.
vec3 trace_path_from(const RenderScene& scene, const PathTracerParams& params, Ray ray, const ClosestHit* known,
                     Sampler& rng, FirstHit& first, PathCounters& counters, PathRecord* record = nullptr);
// The paths of n camera rays whose closest hits are known (a pixel's sample group, n at most
// SceneGeometry::kPacketSize), traced in step: radiance[k] and firsts[k] are what
// trace_path_from gives ray k with rngs[k], bit for bit (the caller has prefetched the first
// hits' textures). Each bounce's rays are all traced and their hits' triangles and corners
// prefetched before any is shaded, so that one path's cache misses overlap the others', where
// a lone path waits for each in turn: on a mesh far larger than the caches.
void trace_paths_from(const RenderScene& scene, const PathTracerParams& params, int n, const Ray* rays,
                      const ClosestHit* known, Sampler* const* rngs, FirstHit* firsts, PathCounters& counters,
                      vec3* radiance);
// What trace_path_from returns, bit for bit, for a camera ray known to hit nothing, without
// the set-up of a path: most camera rays of a small object against the sky end so.
vec3 camera_ray_escaped(const RenderScene& scene, const PathTracerParams& params, const Ray& ray,
                        PathCounters& counters);

}  // namespace tessera
