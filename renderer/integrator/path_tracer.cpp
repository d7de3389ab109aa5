#include "renderer/integrator/path_tracer.h"

#include "renderer/integrator/bsdf.h"
#include "renderer/integrator/punctual_lights.h"

namespace tessera {
namespace {

// Direct light from every punctual light (delta lights: no MIS partner).
vec3 punctual_light_contribution(const RenderScene& scene, const SurfaceHit& s, const Frame& frame,
                                 const Bsdf& bsdf, const vec3& wo_local, PathCounters& counters) {
  vec3 sum(0.0f);
  const vec3 origin = offset_ray_origin(s.p, s.ng);
  for (const PunctualLight& light : scene.description.lights) {
    LightSample ls;
    if (!sample_punctual_light(light, s.p, ls)) continue;
    const vec3 wi_local = frame.to_local(ls.wi);
    const vec3 f = bsdf.eval(wo_local, wi_local);
    if (f == vec3(0.0f) || glm::dot(ls.wi, s.ng) <= 0.0f) continue;
    ++counters.rays;
    if (scene.geometry->occluded(origin, ls.wi, ls.distance * (1.0f - 1e-4f))) continue;
    sum += f * ls.irradiance * wi_local.z;
  }
  return sum;
}

}  // namespace

vec3 trace_path(const RenderScene& scene, const PathTracerParams& params, Ray ray,
                SampleStream& rng, FirstHit& first, PathCounters& counters) {
  vec3 radiance(0.0f), throughput(1.0f);
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
    if (front || sp.double_sided) radiance += throughput * sp.emission;
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
    const vec3 wo_local = frame.to_local(-ray.direction);
    const Bsdf bsdf{sp.base_color};  // Lambertian from baseColor until the glTF BRDF lands
    if (!scene.description.lights.empty())
      radiance += throughput * punctual_light_contribution(scene, s, frame, bsdf, wo_local, counters);

    BsdfSample bs;
    if (!bsdf.sample(wo_local, rng.next2(), bs)) break;
    const vec3 wi = frame.to_world(bs.wi);
    if (glm::dot(wi, s.ng) <= 0.0f) break;  // below the true surface: no light that way
    throughput *= bs.f * (bs.wi.z / bs.pdf);
    if (bounce + 1 >= params.roulette_start) {
      const float survive = std::fmin(1.0f, max_component(throughput));
      if (rng.next() >= survive) break;
      throughput /= survive;
    }
    ray = Ray{offset_ray_origin(s.p, s.ng), wi};
  }
  if (!is_finite(radiance)) {
    ++counters.dropped;
    return vec3(0.0f);
  }
  return radiance;
}

}  // namespace tessera
