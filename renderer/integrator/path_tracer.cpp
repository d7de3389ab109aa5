#include "renderer/integrator/path_tracer.h"

#include "renderer/bsdfs/bsdf.h"
#include "renderer/integrator/guided_scattering.h"
#include "renderer/lights/punctual_lights.h"
#include "renderer/bsdfs/spectrum.h"

namespace tessera {
namespace {

// Straight passes through thin surfaces one path may make: a bound, for rays caught between
// coincident panes.
constexpr int kMaxPasses = 64;

// Veach's power heuristic (beta = 2) for combining two sampling strategies.
inline float power_heuristic(float pdf_a, float pdf_b) {
  const float a = pdf_a * pdf_a, b = pdf_b * pdf_b;
  return a + b > 0.0f ? a / (a + b) : 0.0f;
}

// The weight of an estimate made with `pdf` when the other strategy has `other_pdf`.
float strategy_weight(LightSampling mode, bool is_light_sample, float pdf, float other_pdf) {
  switch (mode) {
    case LightSampling::BsdfOnly: return is_light_sample ? 0.0f : 1.0f;
    case LightSampling::LightsOnly: return is_light_sample ? 1.0f : 0.0f;
    default: return power_heuristic(pdf, other_pdf);
  }
}

// Turns the hit's frame to the side `direction` arrives from, with the shading normal (after
// the normal map) in that hemisphere. True when the ray meets the front face.
bool orient(SurfaceHit& s, const ShadingPoint& sp, const vec3& direction) {
  const bool front = glm::dot(s.ng, direction) < 0.0f;
  if (!front) {
    s.ng = -s.ng;
    s.ns = -s.ns;
  }
  if (sp.normal != vec3(0.0f)) s.ns = front ? sp.normal : -sp.normal;
  // Interpolated or mapped normals can face away from the viewer near silhouettes: there
  // the flat normal is the only consistent choice.
  if (glm::dot(s.ns, s.ng) <= 0.0f || glm::dot(s.ns, direction) >= 0.0f) s.ns = s.ng;
  return front;
}

// A shadow ray crossing a thin-walled transmissive surface: the BSDF's straight pass there,
// the same weight a path sampling that pass carries (SceneGeometry::transmittance).
vec3 thin_transmittance(const void* user, const Ray& ray, const HitRecord& hit) {
  const RenderScene& scene = *static_cast<const RenderScene*>(user);
  SurfaceHit s = scene.geometry->surface(ray, hit);
  const ShadingPoint sp = scene.materials.evaluate(s);
  if (!sp.thin_walled || sp.transmission <= 0.0f || sp.unlit) return vec3(0.0f);
  const bool front = orient(s, sp, ray.direction);
  const Frame frame = Frame::from_normal(s.ns);
  return GltfBsdf(sp, frame.to_local(-ray.direction), front ? sp.ior : 1.0f / sp.ior, frame).straight_transmittance();
}

}  // namespace

vec3 visibility(const RenderScene& scene, const vec3& origin, const vec3& wi, float distance, float time) {
  return scene.geometry->transmittance(origin, wi, distance, time, thin_transmittance, &scene);
}

vec3 visibility_to_surface(const RenderScene& scene, const vec3& from, const vec3& wi, const vec3& on, const vec3& normal,
                           float time) {
  const float to_plane = glm::dot(normal, on - from) / glm::dot(normal, wi);
  if (!(to_plane > 0.0f)) return vec3(1.0f);  // the origin moved past the plane: nothing lies between
  return visibility(scene, from, wi, to_plane * (1.0f - 1e-4f), time);
}

namespace {

struct ShadingContext {
  const SurfaceHit& s;
  const Frame& frame;
  const GltfBsdf& bsdf;
  vec3 wo_local;
  float time;  // the path's: lights and occluders are where they are then
  GuideAt guide;  // directions are drawn from its mixture with the BSDF: its density weighs light samples

  // Ray origin for leaving towards wi: offset to the side of the surface wi goes to.
  vec3 origin_towards(const vec3& wi) const {
    return offset_ray_origin(s.p, glm::dot(wi, s.ng) >= 0.0f ? s.ng : -s.ng, s.extent);
  }
  // What reaches this point along wi from a point on a surface of normal `normal` through
  // `on` (a light's), leaving from the moved origin.
  vec3 visibility_to(const RenderScene& scene, const vec3& wi, const vec3& on, const vec3& normal) const {
    return visibility_to_surface(scene, origin_towards(wi), wi, on, normal, time);
  }
  // A light direction the BSDF can scatter into, with its |cosine| in the shading frame.
  bool usable(const vec3& wi, vec3& wi_local) const {
    const bool above = glm::dot(wi, s.ng) > 0.0f;
    if (!above && !bsdf.has_transmission()) return false;
    wi_local = frame.to_local(wi);
    return (wi_local.z > 0.0f) == above;  // shading and true geometry must agree on the side
  }
};

// Direct light from punctual light i (a delta light: no MIS partner).
vec3 punctual_light(const RenderScene& scene, const ShadingContext& c, std::size_t i, PathCounters& counters) {
  const PunctualLight& light = scene.description.lights[i];
  const MotionTransform& motion = scene.light_motion[i];
  const LightPlacement at = motion.empty() ? LightPlacement{light.position, light.direction}
                                           : light_placement(motion.at(c.time));
  LightSample ls;
  vec3 wi_local;
  if (!sample_punctual_light(light, at, c.s.p, ls) || !c.usable(ls.wi, wi_local)) return vec3(0.0f);
  const vec3 f = c.bsdf.eval(c.wo_local, wi_local);
  if (f == vec3(0.0f)) return vec3(0.0f);
  ++counters.rays;
  const vec3 through = visibility(scene, c.origin_towards(ls.wi), ls.wi, ls.distance * (1.0f - 1e-4f), c.time);
  return through * f * ls.irradiance * std::fabs(wi_local.z);
}

// Direct light from every punctual light.
vec3 punctual_light_contribution(const RenderScene& scene, const ShadingContext& c, PathCounters& counters) {
  vec3 sum(0.0f);
  for (std::size_t i = 0; i < scene.description.lights.size(); ++i) sum += punctual_light(scene, c, i, counters);
  return sum;
}

// Direct light from the punctual lights through the light tree: every directional light, and
// one point or spot light chosen by `u` in proportion to its bound at this point, divided by
// the probability of that choice.
vec3 punctual_lights_by_tree(const RenderScene& scene, const ShadingContext& c, float u, PathCounters& counters) {
  vec3 sum(0.0f);
  for (std::uint32_t i : scene.light_tree.directional()) sum += punctual_light(scene, c, i, counters);
  const LightTree::Choice pick = scene.light_tree.sample(c.s.p, c.s.ns, u);
  if (pick.pmf > 0.0f) sum += punctual_light(scene, c, pick.light, counters) / pick.pmf;
  return sum;
}

// One light sample on the emissive triangles, weighted against BSDF sampling (MIS).
// `u`: the point (x, y) and the light (z, which chose `light`), stratified together.
vec3 area_light_contribution(const RenderScene& scene, const ShadingContext& c, const vec3& u, const AreaLights::Choice& light,
                             LightSampling mode, PathCounters& counters) {
  AreaLightSample ls;
  vec3 wi_local;
  if (!scene.area_lights->sample(c.s.p, c.time, light, {u.x, u.y}, ls) || !c.usable(ls.wi, wi_local)) return vec3(0.0f);
  float bsdf_pdf;
  const vec3 f = c.bsdf.eval(c.wo_local, wi_local, bsdf_pdf);
  if (f == vec3(0.0f)) return vec3(0.0f);
  const vec3 radiance = scene.area_lights->radiance(light, ls);  // its texels fetched during eval
  if (radiance == vec3(0.0f)) return vec3(0.0f);
  ++counters.rays;
  const vec3 through = c.visibility_to(scene, ls.wi, ls.p, ls.normal);
  if (through == vec3(0.0f)) return vec3(0.0f);
  const float weight = strategy_weight(mode, true, ls.pdf, c.guide.pdf(ls.wi, bsdf_pdf));
  return through * f * radiance * (std::fabs(wi_local.z) * weight / ls.pdf);
}

// One direction towards the environment image, weighted against BSDF sampling (MIS).
vec3 environment_contribution(const RenderScene& scene, const ShadingContext& c, Sampler& rng,
                              LightSampling mode, PathCounters& counters) {
  const vec2 u = rng.next2();
  float pdf;
  const vec3 wi = scene.environment.sample(u, pdf);
  vec3 wi_local;
  if (!(pdf > 0.0f) || !c.usable(wi, wi_local)) return vec3(0.0f);
  float bsdf_pdf;
  const vec3 f = c.bsdf.eval(c.wo_local, wi_local, bsdf_pdf);
  if (f == vec3(0.0f)) return vec3(0.0f);
  ++counters.rays;
  const vec3 through = visibility(scene, c.origin_towards(wi), wi, std::numeric_limits<float>::infinity(), c.time);
  if (through == vec3(0.0f)) return vec3(0.0f);
  const float weight = strategy_weight(mode, true, pdf, c.guide.pdf(wi, bsdf_pdf));
  return through * f * scene.environment.radiance(wi) * (std::fabs(wi_local.z) * weight / pdf);
}

// Denoising features through mirrors (after Cycles' denoising passes): a vertex whose
// scattering is mostly (3/4 or more) metal or transmission with GGX alpha at most 0.0025
// (roughness 0.05) shows what it reflects or refracts, which its own albedo and normal cannot
// explain; the albedo and normal then come from the next vertex, the albedo weighted by the
// mirror bounces' throughput, or the albedo is the environment's radiance times that
// throughput where the continued path leaves the scene (depth stays the first hit's).
// Cycles continues up to alpha 0.075; here glossier surfaces' features were too noisy to help
// (DamagedHelmet's visor measured worse with them).
bool features_look_through(const ShadingPoint& sp) {
  constexpr float kMirrorAlpha = 0.0025f;
  const float smooth = sp.roughness * sp.roughness <= kMirrorAlpha ? sp.metallic + (1.0f - sp.metallic) * sp.transmission : 0.0f;
  return smooth >= 0.75f;
}

// A sample's radiance as the film takes it: a non-finite one dropped (counted), the
// luminance clamped when asked.
vec3 finished_sample(vec3 radiance, const PathTracerParams& params, PathCounters& counters) {
  if (!is_finite(radiance)) {
    ++counters.dropped;
    return vec3(0.0f);
  }
  if (params.clamp > 0.0f) {
    const float l = luminance(radiance);
    if (l > params.clamp) radiance *= params.clamp / l;
  }
  return radiance;
}

}  // namespace

vec3 trace_path(const RenderScene& scene, const PathTracerParams& params, Ray ray,
                Sampler& rng, FirstHit& first, PathCounters& counters, PathRecord* record) {
  return trace_path_from(scene, params, ray, nullptr, rng, first, counters, record);
}

namespace {

// What a path carries from one vertex to the next (trace_path_from's loop, or a group of
// paths traced in step).
struct PathState {
  void start(const Ray& r, bool known) { *this = PathState{}, ray = r, time = r.time, prefetched = known; }
  Ray ray;
  float time = 0.0f;  // every ray of the path looks at the scene at the camera ray's time
  vec3 radiance{0.0f}, throughput{1.0f};
  // The refractions' radiance scaling (1 / eta^2 entering glass) undone, for Russian roulette
  // alone (pbrt-v4's etaScale): a path inside glass has lost no energy, only scale.
  float eta_scale = 1.0f;
  vec3 absorption{0.0f};  // of the volume the ray travels in (Beer-Lambert); 0 = none
  float bsdf_pdf = 0.0f;  // solid-angle pdf of the direction that led here; 0 = camera ray
  // The vertex that direction left from, as the emitter tree chose a light for it: what an
  // emitter's MIS weight at the end of the direction needs (with PathTracerParams::emitter_tree).
  AreaLights::ShadingPlace from;
  // Straight passes through thin surfaces since the last scattering: they do not count as
  // bounces, and the light a pass reaches is weighed against light sampling from that
  // vertex, as far away as the whole straight line.
  float passed = 0.0f;
  int passes = 0;
  int blend_passes = 0;  // BLEND surfaces passed (pass_blend), bounded like the straight passes
  // The wavelength (nm) this path carries since its first dispersive surface; 0 = none yet
  // (spectrum.h: the throughput then holds the wavelength's RGB weight).
  float wavelength = 0.0f;
  bool features_pending = true;  // the features still look through smooth vertices
  vec3 feature_weight{1.0f};  // the smooth bounces' throughput since the first hit
  int bounce = 0;
  HitRecord hit;  // of `ray`, once traced
  bool prefetched = false;  // the hit's textures were prefetched with others' (a packet, a group)
  GuidePath* learning = nullptr;  // what the path records for the guide, while it learns

  // On along the same line past the surface s just hit, as if it were absent, counted in
  // `count` (passes or blend_passes); false past kMaxPasses of them.
  bool go_past(const SurfaceHit& s, int& count) {
    if (++count > kMaxPasses) return false;
    passed += hit.t;
    const vec3 side = glm::dot(ray.direction, s.ng) >= 0.0f ? s.ng : -s.ng;
    ray = Ray{offset_ray_origin(s.p, side, s.extent), ray.direction, 0.0f, std::numeric_limits<float>::infinity(), time};
    return true;
  }
};

// The probability that a path passes a BLEND surface of opacity alpha where it meets it (the
// rest see the surface): (1 - alpha) / ((1 - alpha) + alpha * A), with A what the surface
// returns of uniform light as its base colour tells (Schlick's 4% over a dielectric's base,
// a metal's base; its emission added; kept in [0.1, 1]). So where the surface is dark and
// the view behind it bright, most samples go where the light is, as Cycles weighs its
// transparent closure against the surface's closures. Any choice in (0, 1) is unbiased: the
// path is divided by the probability of what it chose.
float blend_pass_probability(float alpha, const ShadingPoint& sp) {
  const float base = luminance(sp.base_color);
  const float albedo = sp.metallic * base + (1.0f - sp.metallic) * (0.04f + 0.96f * base);
  const float seen = alpha * glm::clamp(albedo + luminance(sp.emission), 0.1f, 1.0f);
  return (1.0f - alpha) / ((1.0f - alpha) + seen);
}

// On past a BLEND surface (chosen with probability `chance`, weighed by `weight`) as if it
// were absent, as its cut-outs are: not a bounce, not a pass of the camera ray (features,
// transparent background), and weighed against light sampling from the last vertex like a
// straight pass. The choice is a draw of the path's sampler, so over a pixel's samples the
// share that passes is stratified, where a hash of each ray was white noise. False (the path
// ends) past kMaxPasses of them: a ray caught between coincident layers.
bool pass_blend(PathState& st, const SurfaceHit& s, float chance, float weight, PathRecord* record) {
  if (record) {
    PathVertex& v = record->vertices.emplace_back();
    v.position = s.p, v.normal = s.ng, v.material = s.material, v.throughput = st.throughput;
    v.lobe = "alpha pass", v.pdf = chance;
  }
  if (!st.go_past(s, st.blend_passes)) {
    if (record) record->end = "too many alpha layers";
    return false;
  }
  st.throughput *= weight;
  return true;
}

// The path's vertex at st.hit (`found`: st.ray hit something): what it adds to st.radiance,
// and st.ray made the next ray; false when the path ends there.
bool path_vertex(const RenderScene& scene, const PathTracerParams& params, PathState& st, bool found, Sampler& rng,
                 FirstHit& first, PathCounters& counters, PathRecord* record) {
  Ray& ray = st.ray;
  HitRecord& hit = st.hit;
  vec3 &radiance = st.radiance, &throughput = st.throughput, &absorption = st.absorption, &feature_weight = st.feature_weight;
  float &eta_scale = st.eta_scale, &bsdf_pdf = st.bsdf_pdf, &passed = st.passed, &wavelength = st.wavelength;
  int &passes = st.passes, &bounce = st.bounce;
  bool& features_pending = st.features_pending;
  const float time = st.time;
  const LightSampling mode = params.light_sampling;
  const bool light_sampling = !scene.area_lights->empty() && mode != LightSampling::BsdfOnly;
  const bool environment_sampling = scene.environment.has_image() && mode != LightSampling::BsdfOnly;
  auto record_features = [&](const ShadingPoint& sp, const SurfaceHit& s) {
    if (bounce == 0 && passes == 0) first = {true, sp.base_color, s.ns, passed + hit.t};
    else if (features_pending) first.albedo = feature_weight * sp.base_color, first.normal = s.ns;
  };
  if (absorption != vec3(0.0f)) throughput *= found ? glm::exp(-absorption * hit.t) : vec3(0.0f);
  if (!found) {
    const float weight = bsdf_pdf > 0.0f && environment_sampling
                             ? strategy_weight(mode, false, bsdf_pdf, scene.environment.pdf(ray.direction))
                             : 1.0f;
    const bool camera_miss = bounce == 0 && passes == 0;
    if (!(camera_miss && params.transparent_background)) {
      radiance += throughput * scene.environment.radiance(ray.direction) * weight;
      if (record) record->escaped = throughput * scene.environment.radiance(ray.direction) * weight;
    }
    if (record) record->end = "left the scene";
    if (features_pending && (bounce > 0 || passes > 0)) first.albedo = feature_weight * scene.environment.radiance(ray.direction);
    return false;
  }
  SurfaceHit s = scene.geometry->surface(ray, hit);
  if (!st.prefetched) scene.materials.prefetch_textures(s);
  st.prefetched = false;
  // A BLEND surface in part there: the draw that chooses to pass it comes first. (A MASK
  // surface met is opaque: the filter has cut it out elsewhere.)
  const Material& material = scene.materials.material(s.material);
  const float alpha = material.alpha_mode == AlphaMode::Blend ? scene.materials.opacity(s.material, s.uv, s.color) : 1.0f;
  const float u_blend = alpha < 1.0f ? rng.next() : 0.0f;
  // The emitter light sampling will use: its three numbers come next in the sequence unless
  // this vertex draws a wavelength first, so then it is chosen here, and its record arrives
  // while the material is evaluated; otherwise after the wavelength. A path that ends before
  // light sampling leaves the numbers unused, and draws nothing after them.
  const bool last = bounce >= params.max_bounces;
  vec3 u_light(0.0f);
  AreaLights::Choice light;
  bool light_chosen = false;
  // Where the emitter tree chooses for: the hit and its geometric normal (either side will do).
  const AreaLights::ShadingPlace place{s.p, s.ng};
  auto choose_light = [&] {
    u_light = rng.next3();
    light = scene.area_lights->choose(u_light.z, params.emitter_pick, params.emitter_tree ? &place : nullptr);
    light_chosen = true;
  };
  if (light_sampling && !last && !(wavelength == 0.0f && material.dispersion > 0.0f))
    choose_light();
  ShadingPoint sp = scene.materials.evaluate(s);
  if (alpha < 1.0f) {
    const float pass = blend_pass_probability(alpha, sp);
    if (u_blend < pass) return pass_blend(st, s, pass, (1.0f - alpha) / pass, record);
    throughput *= alpha / (1.0f - pass);
  }
  PathVertex* vertex = nullptr;
  if (record) {
    vertex = &record->vertices.emplace_back();
    vertex->position = s.p, vertex->normal = s.ns, vertex->material = s.material, vertex->throughput = throughput;
  }
  if ((glm::dot(s.ng, ray.direction) < 0.0f || sp.double_sided) && sp.emission != vec3(0.0f)) {
    // Light sampling could have found this point too: weigh the two strategies.
    SurfaceHit from_vertex = s;
    from_vertex.t += passed;
    const float weight =
        bsdf_pdf > 0.0f && light_sampling
            ? strategy_weight(mode, false, bsdf_pdf,
                              scene.area_lights->pdf(hit, from_vertex, ray.direction, params.emitter_pick,
                                                     params.emitter_tree ? &st.from : nullptr))
            : 1.0f;
    radiance += throughput * sp.emission * weight;
    if (vertex) vertex->emitted = throughput * sp.emission * weight;
  }
  if (sp.unlit) {  // KHR_materials_unlit: the colour is what the surface shows
    radiance += throughput * sp.base_color;
    record_features(sp, s);
    if (vertex) vertex->emitted += throughput * sp.base_color, record->end = "unlit surface";
    return false;
  }
  const bool front = orient(s, sp, ray.direction);
  if (vertex) vertex->normal = s.ns;
  record_features(sp, s);
  features_pending = features_pending && features_look_through(sp);
  if (last && !(sp.thin_walled && sp.transmission > 0.0f)) {
    if (record) record->end = "max bounces";
    return false;
  }

  if (sp.dispersion > 0.0f && sp.transmission > 0.0f) {  // KHR_materials_dispersion
    if (wavelength == 0.0f) {
      const WavelengthSample w = sample_wavelength(rng.next());
      wavelength = w.lambda;
      throughput *= w.weight;
    }
    sp.ior = dispersive_ior(sp.ior, sp.dispersion, wavelength);
  }
  if (light_sampling && !last && !light_chosen) choose_light();
  const Frame frame = Frame::from_normal(s.ns);
  const vec3 wo_local = frame.to_local(-ray.direction);
  const float eta = front ? sp.ior : 1.0f / sp.ior;
  const GltfBsdf bsdf(sp, wo_local, eta, frame);
  const ShadingContext ctx{s, frame, bsdf, wo_local, time, guide_at(params.guide, s.p, sp, bsdf)};
  if (last) {  // no scattering left, but the straight pass is none: it goes on, weighted
    throughput *= bsdf.straight_transmittance();
    if (vertex) vertex->lobe = "straight pass";
    if (features_pending) feature_weight *= bsdf.straight_transmittance();
    return throughput != vec3(0.0f) && st.go_past(s, passes);
  }
  vec3 direct(0.0f);  // what light sampling adds, summed for the record only
  auto add_direct = [&](const vec3& light) {
    const vec3 added = throughput * light;
    radiance += added;
    direct += added;
  };
  if (params.light_tree)  // one punctual light from the tree: its own draw
    add_direct(punctual_lights_by_tree(scene, ctx, rng.next(), counters));
  else if (!scene.description.lights.empty())
    add_direct(punctual_light_contribution(scene, ctx, counters));
  if (light_sampling) add_direct(area_light_contribution(scene, ctx, u_light, light, mode, counters));
  if (environment_sampling) add_direct(environment_contribution(scene, ctx, rng, mode, counters));
  if (vertex) vertex->direct = direct;

  BsdfSample bs;
  const vec3 u = rng.next3();  // the direction (x, y) and the lobe (z), stratified together
  if (!sample_guided(bsdf, frame, wo_local, ctx.guide, u, bs)) {
    if (record) record->end = "no direction sampled";
    return false;
  }
  if (vertex) vertex->lobe = bs.passthrough ? "straight pass" : GltfBsdf::lobe_name(bs.lobe), vertex->pdf = bs.pdf;
  throughput *= bs.f * (std::fabs(bs.wi.z) / bs.pdf);
  if (features_pending) feature_weight *= bs.f * (std::fabs(bs.wi.z) / bs.pdf);
  if (bs.passthrough) return st.go_past(s, passes);
  const vec3 wi = frame.to_world(bs.wi);
  if ((glm::dot(wi, s.ng) > 0.0f) == bs.transmitted) {  // shading and geometry disagree
    if (record) record->end = "direction below the surface";
    return false;
  }
  bsdf_pdf = bs.pdf;
  st.from = place;
  passed = 0.0f;
  if (bs.transmitted && !sp.thin_walled) absorption = front ? sp.absorption : vec3(0.0f);
  if (bs.transmitted && bs.lobe == GltfBsdf::kTransmission) eta_scale *= sqr(eta);
  if (++bounce >= params.roulette_start) {
    // The square root (as Cycles takes) ends paths later than the throughput itself would:
    // on a bright background the light a path still gathers is not small when its
    // throughput is (docs/performance.md, "Russian roulette").
    const float survive = fmin_inline(1.0f, std::sqrt(max_component(throughput) * eta_scale));
    if (rng.next() >= survive) {
      if (record) record->end = "Russian roulette";
      return false;
    }
    throughput /= survive;
  }
  ray = Ray{ctx.origin_towards(wi), wi, 0.0f, std::numeric_limits<float>::infinity(), time};
  if (st.learning && ctx.guide.share > 0.0f) st.learning->vertex(s.p, wi, bs.pdf, throughput, radiance);
  return true;
}

}  // namespace

vec3 trace_path_from(const RenderScene& scene, const PathTracerParams& params, Ray ray, const ClosestHit* known,
                     Sampler& rng, FirstHit& first, PathCounters& counters, PathRecord* record) {
  PathState st;
  st.start(ray, known != nullptr);  // a camera packet's textures are prefetched together
  GuidePath learning;
  if (params.learn) st.learning = &learning;
  for (;;) {
    ++counters.rays;
    const bool found = known ? (st.hit = known->hit, known->found) : scene.geometry->intersect(st.ray, st.hit);
    known = nullptr;  // the first ray's only
    if (!path_vertex(scene, params, st, found, rng, first, counters, record)) break;
  }
  if (params.learn) learning.finish(*params.guide, st.radiance);
  return finished_sample(st.radiance, params, counters);
}

void trace_paths_from(const RenderScene& scene, const PathTracerParams& params, int n, const Ray* rays,
                      const ClosestHit* known, Sampler* const* rngs, FirstHit* firsts, PathCounters& counters,
                      vec3* radiance) {
  constexpr int kMost = SceneGeometry::kPacketSize;
  PathState states[kMost];
  GuidePath learning[kMost];
  bool found[kMost];
  int active[kMost], count = 0;
  for (int k = 0; k < n && k < kMost; ++k) {
    states[k].start(rays[k], true);  // the caller prefetched the first hits' textures
    if (params.learn) states[k].learning = &learning[k];
    states[k].hit = known[k].hit;
    found[k] = known[k].found;
    ++counters.rays;
    active[count++] = k;
  }
  const SceneGeometry& geometry = *scene.geometry;
  while (count > 0) {
    int still = 0;
    for (int a = 0; a < count; ++a) {
      const int k = active[a];
      if (path_vertex(scene, params, states[k], found[k], *rngs[k], firsts[k], counters, nullptr)) active[still++] = k;
      else {
        if (params.learn) learning[k].finish(*params.guide, states[k].radiance);
        radiance[k] = finished_sample(states[k].radiance, params, counters);
      }
    }
    count = still;
    for (int a = 0; a < count; ++a) {
      PathState& st = states[active[a]];
      ++counters.rays;
      found[active[a]] = geometry.intersect(st.ray, st.hit);
      if (found[active[a]]) geometry.prefetch_triangle(st.hit);
    }
    for (int a = 0; a < count; ++a)
      if (found[active[a]]) geometry.prefetch_corners(states[active[a]].hit);
  }
}

vec3 camera_ray_escaped(const RenderScene& scene, const PathTracerParams& params, const Ray& ray,
                        PathCounters& counters) {
  ++counters.rays;
  vec3 radiance(0.0f);
  // trace_path_from's expression for the background, weight 1, throughput 1: the same bits.
  if (!params.transparent_background) radiance += vec3(1.0f) * scene.environment.radiance(ray.direction) * 1.0f;
  return finished_sample(radiance, params, counters);
}

}  // namespace tessera
