#include "renderer/integrator/path_tracer.h"

#include "renderer/integrator/bsdf.h"
#include "renderer/integrator/punctual_lights.h"

namespace tessera {
namespace {

// Veach's power heuristic (beta = 2) for combining two sampling strategies.
inline float power_heuristic(float pdf_a, float pdf_b) {
  const float a = pdf_a * pdf_a, b = pdf_b * pdf_b;
  return a + b > 0.0f ? a / (a + b) : 0.0f;
}

struct ShadingContext {
  const SurfaceHit& s;
  const Frame& frame;
  const Bsdf& bsdf;
  vec3 wo_local;
  vec3 origin;  // offset ray origin for rays leaving this point
};

// Direct light from every punctual light (delta lights: no MIS partner).
vec3 punctual_light_contribution(const RenderScene& scene, const ShadingContext& c, PathCounters& counters) {
  vec3 sum(0.0f);
  for (const PunctualLight& light : scene.description.lights) {
    LightSample ls;
    if (!sample_punctual_light(light, c.s.p, ls) || glm::dot(ls.wi, c.s.ng) <= 0.0f) continue;
    const vec3 wi_local = c.frame.to_local(ls.wi);
    const vec3 f = c.bsdf.eval(c.wo_local, wi_local);
    if (f == vec3(0.0f)) continue;
    ++counters.rays;
    if (scene.geometry->occluded(c.origin, ls.wi, ls.distance * (1.0f - 1e-4f))) continue;
    sum += f * ls.irradiance * wi_local.z;
  }
  return sum;
}

// One light sample on the emissive triangles, weighted against BSDF sampling (MIS).
vec3 area_light_contribution(const RenderScene& scene, const ShadingContext& c, SampleStream& rng,
                             PathCounters& counters) {
  const float u_select = rng.next();
  const vec2 u_point = rng.next2();
  AreaLightSample ls;
  if (!scene.area_lights->sample(c.s.p, u_select, u_point, ls) || glm::dot(ls.wi, c.s.ng) <= 0.0f) return vec3(0.0f);
  const vec3 wi_local = c.frame.to_local(ls.wi);
  const vec3 f = c.bsdf.eval(c.wo_local, wi_local);
  if (f == vec3(0.0f) || ls.radiance == vec3(0.0f)) return vec3(0.0f);
  ++counters.rays;
  if (scene.geometry->occluded(c.origin, ls.wi, ls.distance * (1.0f - 1e-4f))) return vec3(0.0f);
  const float weight = power_heuristic(ls.pdf, c.bsdf.pdf(c.wo_local, wi_local));
  return f * ls.radiance * (wi_local.z * weight / ls.pdf);
}

}  // namespace

vec3 trace_path(const RenderScene& scene, const PathTracerParams& params, Ray ray,
                SampleStream& rng, FirstHit& first, PathCounters& counters) {
  vec3 radiance(0.0f), throughput(1.0f);
  float bsdf_pdf = 0.0f;  // solid-angle pdf of the direction that led here; 0 = camera ray
  const bool light_sampling = !scene.area_lights->empty();
  for (int bounce = 0;; ++bounce) {
    HitRecord hit;
    ++counters.rays;
    if (!scene.geometry->intersect(ray, hit)) {
      radiance += throughput * scene.environment.radiance(ray.direction);
      break;
    }
    SurfaceHit s = scene.geometry->surface(ray, hit);
    const ShadingPoint sp = scene.materials.evaluate(s);
    const bool front = glm::dot(s.ng, ray.direction) < 0.0f;
    if ((front || sp.double_sided) && sp.emission != vec3(0.0f)) {
      // Light sampling could have found this point too: weigh the two strategies.
      const float weight = bsdf_pdf > 0.0f && light_sampling
                               ? power_heuristic(bsdf_pdf, scene.area_lights->pdf(hit, s, ray.direction))
                               : 1.0f;
      radiance += throughput * sp.emission * weight;
    }
    // Shade the side the ray arrived on; keep the shading normal in that hemisphere.
    if (!front) {
      s.ng = -s.ng;
      s.ns = -s.ns;
    }
    // Interpolated normals can face away from the viewer near silhouettes: there the
    // flat normal is the only consistent choice.
    if (glm::dot(s.ns, s.ng) <= 0.0f || glm::dot(s.ns, ray.direction) >= 0.0f) s.ns = s.ng;
    if (bounce == 0) first = {true, sp.base_color, s.ns, hit.t};
    if (bounce >= params.max_bounces) break;

    const Frame frame = Frame::from_normal(s.ns);
    const Bsdf bsdf{sp.base_color};  // Lambertian from baseColor until the glTF BRDF lands
    const ShadingContext ctx{s, frame, bsdf, frame.to_local(-ray.direction), offset_ray_origin(s.p, s.ng)};
    if (!scene.description.lights.empty()) radiance += throughput * punctual_light_contribution(scene, ctx, counters);
    if (light_sampling) radiance += throughput * area_light_contribution(scene, ctx, rng, counters);

    BsdfSample bs;
    if (!bsdf.sample(ctx.wo_local, rng.next2(), bs)) break;
    const vec3 wi = frame.to_world(bs.wi);
    if (glm::dot(wi, s.ng) <= 0.0f) break;  // below the true surface: no light that way
    throughput *= bs.f * (bs.wi.z / bs.pdf);
    bsdf_pdf = bs.pdf;
    if (bounce + 1 >= params.roulette_start) {
      const float survive = std::fmin(1.0f, max_component(throughput));
      if (rng.next() >= survive) break;
      throughput /= survive;
    }
    ray = Ray{ctx.origin, wi};
  }
  if (!is_finite(radiance)) {
    ++counters.dropped;
    return vec3(0.0f);
  }
  return radiance;
}

}  // namespace tessera
