#include "renderer/integrator/emitter_pick.h"

#include "renderer/bsdfs/bsdf.h"
#include "renderer/integrator/path_tracer.h"
#include "renderer/sampling/sampler.h"

namespace tessera {
namespace {

// A uniform background of no light competes with nothing.
bool background_is_dark(const Environment& environment) {
  return !environment.has_image() && environment.radiance(vec3(0.0f, 0.0f, 1.0f)) == vec3(0.0f);
}

struct DirectLight {
  double emitters = 0.0, background = 0.0;  // luminance of irradiance, summed over the pilot
};

// Irradiance at a camera hit from the emitters (light samples by power) and from the background
// (cosine-weighted directions), one estimate of each per direction, with visibility, on the
// side the camera sees. Materials are left out: the share is of the light, not of a BSDF.
void add_direct_light(const RenderScene& scene, const Ray& ray, const HitRecord& hit, std::uint32_t px, std::uint32_t py,
                      const EmitterPickParams& params, DirectLight& sum) {
  const SurfaceHit s = scene.geometry->surface(ray, hit);
  const vec3 n = glm::dot(s.ng, ray.direction) < 0.0f ? s.ng : -s.ng;
  const vec3 origin = offset_ray_origin(s.p, n, s.extent);
  const Frame frame = Frame::from_normal(n);
  for (int k = 0; k < params.directions; ++k) {
    Sampler rng(SamplerKind::independent, px, py, static_cast<std::uint32_t>(k), 0x9e1c7u);
    const vec3 u = rng.next3();
    AreaLightSample ls;
    const AreaLights::Choice light = scene.area_lights->choose(u.z);
    if (scene.area_lights->sample(s.p, params.time, light, {u.x, u.y}, ls)) {
      const float cosine = glm::dot(ls.wi, n);
      if (cosine > 0.0f) {
        const vec3 through = visibility_to_surface(scene, origin, ls.wi, ls.p, ls.normal, params.time);
        sum.emitters += luminance(through * scene.area_lights->radiance(light, ls)) * cosine / ls.pdf;
      }
    }
    const vec3 wi = frame.to_world(sample_cosine_hemisphere(rng.next2()));
    const vec3 through = visibility(scene, origin, wi, std::numeric_limits<float>::infinity(), params.time);
    sum.background += kPi * luminance(through * scene.environment.radiance(wi));  // cos / pdf = pi
  }
}

}  // namespace

float emitter_pick_probability(const RenderScene& scene, const RenderCamera& camera, const EmitterPickParams& params) {
  if (scene.area_lights->empty() || background_is_dark(scene.environment)) return 1.0f;
  DirectLight sum;
  for (int j = 0; j < params.grid; ++j)
    for (int i = 0; i < params.grid; ++i) {
      const vec2 film((i + 0.5f) / params.grid, (j + 0.5f) / params.grid);
      const Ray ray = camera.generate_ray(film, vec2(0.5f), params.time);
      HitRecord hit;
      if (is_finite(ray.origin) && is_finite(ray.direction) && scene.geometry->intersect(ray, hit))
        add_direct_light(scene, ray, hit, static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j), params, sum);
    }
  const double total = sum.emitters + sum.background;
  if (!(total > 0.0) || !std::isfinite(total)) return 1.0f;  // the pilot saw no light: no reason to skip
  const double q = sum.emitters / total / params.full_share;
  return static_cast<float>(std::clamp(q, static_cast<double>(params.floor), 1.0));
}

double emitter_tree_gain(const RenderScene& scene, const RenderCamera& camera, const EmitterTreeParams& params) {
  const AreaLights& lights = *scene.area_lights;
  if (lights.empty() || lights.tree().empty()) return 1.0;
  double variance[2] = {0.0, 0.0};  // by power, by the tree: summed over the hits
  for (int j = 0; j < params.grid; ++j)
    for (int i = 0; i < params.grid; ++i) {
      const vec2 film((i + 0.5f) / params.grid, (j + 0.5f) / params.grid);
      const Ray ray = camera.generate_ray(film, vec2(0.5f), params.time);
      HitRecord hit;
      if (!(is_finite(ray.origin) && is_finite(ray.direction) && scene.geometry->intersect(ray, hit))) continue;
      const SurfaceHit s = scene.geometry->surface(ray, hit);
      const vec3 n = glm::dot(s.ng, ray.direction) < 0.0f ? s.ng : -s.ng;
      const vec3 origin = offset_ray_origin(s.p, n, s.extent);
      const AreaLights::ShadingPlace place{s.p, s.ng};  // as the path tracer chooses
      for (int way = 0; way < 2; ++way) {
        double sum = 0.0, sum2 = 0.0;
        for (int k = 0; k < params.directions; ++k) {
          Sampler rng(SamplerKind::independent, static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j),
                      static_cast<std::uint32_t>(k), 0x7e3au);
          const vec3 u = rng.next3();
          AreaLightSample ls;
          const AreaLights::Choice light = lights.choose(u.z, 1.0f, way ? &place : nullptr);
          double f = 0.0;
          if (lights.sample(s.p, params.time, light, {u.x, u.y}, ls)) {
            const float cosine = glm::dot(ls.wi, n);
            if (cosine > 0.0f) {
              const vec3 through = visibility_to_surface(scene, origin, ls.wi, ls.p, ls.normal, params.time);
              f = luminance(through * lights.radiance(light, ls)) * cosine / ls.pdf;
            }
          }
          sum += f, sum2 += f * f;
        }
        const double k = params.directions;
        variance[way] += std::max(sum2 / k - (sum / k) * (sum / k), 0.0) * k / (k - 1.0);
      }
    }
  if (!(variance[1] > 0.0)) return variance[0] > 0.0 ? std::numeric_limits<double>::infinity() : 1.0;
  return variance[0] / variance[1];
}

bool emitter_tree_used(const RenderScene& scene, const RenderCamera& camera, LightTreeUse use,
                       const EmitterTreeParams& params) {
  if (scene.area_lights->tree().empty() || use == LightTreeUse::Off) return false;
  return use == LightTreeUse::On || emitter_tree_gain(scene, camera, params) >= params.gain;
}

}  // namespace tessera
