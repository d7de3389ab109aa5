#include "renderer/lights/area_lights.h"

#include <algorithm>

#include <tbb/parallel_for.h>

namespace tessera {
namespace {

// Upper bound of the radiance a material can emit, for choosing lights by power.
float emitted_luminance(const Material& m) {
  return luminance(m.emissive_factor) * m.emissive_strength;
}

// Mean emitted luminance of a textured emitter over its triangle, from four points (the
// centre and halfway to each corner): emitters mostly dark in their texture (a helmet's
// glowing details) are then rarely chosen. A small floor keeps every emitter reachable by
// light sampling alone; with MIS, BSDF sampling covers whatever light sampling misses.
double textured_luminance(const MaterialTable& materials, const Material& m, const TextureCorners& texturing) {
  static const float kPoints[4][2] = {{1 / 3.f, 1 / 3.f}, {2 / 3.f, 1 / 6.f}, {1 / 6.f, 2 / 3.f}, {1 / 6.f, 1 / 6.f}};
  double sum = 0.0;
  for (const auto& b : kPoints) sum += luminance(materials.emission(texturing.at(b[0], b[1])));
  return std::max(sum / 4.0, 0.01 * emitted_luminance(m));
}

// Triangles in a leaf of the light tree at most: a shallower walk (each level two bounds'
// importance), and a leaf's few neighbours chosen by power alone.
constexpr int kTreeLeaf = 8;

HitRecord at_time(HitRecord where, float time) {
  where.time = time;
  return where;
}

}  // namespace

AreaLights::AreaLights(const SceneDescription& scene, const SceneGeometry& geometry, const MaterialTable& materials)
    : geometry_(geometry), materials_(materials) {
  std::vector<double> power;
  std::vector<std::pair<std::size_t, const Material*>> textured_triangles;  // their power needs the texture
  std::vector<LightBounds> bounds;  // for the tree; power below
  const std::vector<SceneGeometry::PlacedPrimitive> placed = geometry.placed_primitives();
  std::vector<Bounds3> shutter;  // each list's box over the shutter, when something moves
  for (std::size_t list = 0; list < placed.size(); ++list) {
    const SceneGeometry::PlacedPrimitive& pp = placed[list];
    const Material& m = materials.material(pp.mesh->material);
    const float le = emitted_luminance(m);
    if (!(le > 0.0f)) continue;
    first_[list_key(pp.geom, pp.instance)] = static_cast<std::uint32_t>(triangles_.size());
    const auto& idx = pp.mesh->indices;
    for (std::uint32_t t = 0; 3 * t + 2 < idx.size(); ++t) {
      const vec3 p0 = vec3(pp.to_world * vec4(pp.mesh->positions[idx[3 * t]], 1.0f));
      const vec3 p1 = vec3(pp.to_world * vec4(pp.mesh->positions[idx[3 * t + 1]], 1.0f));
      const vec3 p2 = vec3(pp.to_world * vec4(pp.mesh->positions[idx[3 * t + 2]], 1.0f));
      const float area = 0.5f * glm::length(glm::cross(p1 - p0, p2 - p0));
      HitRecord where;
      where.geom = pp.geom;
      where.instance = pp.instance;
      where.prim = t;
      // Every triangle keeps its slot (so a hit maps to it by index); degenerate ones get
      // no power and are never chosen.
      // The front-side normal exactly as shading sees it (winding, mirroring, and normals).
      where.u = where.v = 1.0f / 3.0f;
      const SurfaceHit centre = geometry.surface(Ray{p0, vec3(0, 0, 1)}, where);
      const vec3 constant = m.emissive_factor * m.emissive_strength;
      const bool textured = m.emissive_texture.present();
      const TextureCorners texturing = textured ? geometry.texture_corners(where) : TextureCorners{};
      Triangle tri;
      tri.shape = {p0, p1 - p0, p2 - p0, centre.ng, area};
      tri.textured = textured;
      tri.double_sided = m.double_sided;
      tri.moves = pp.moves;
      tri.texturing = texturing;
      tri.radiance = constant;
      tri.where = where;
      double mean_area = area;
      LightBounds b;
      b.lo = glm::min(p0, glm::min(p1, p2));
      b.hi = glm::max(p0, glm::max(p1, p2));
      b.axis = centre.ng;
      b.cos_spread = m.double_sided ? -1.0f : 1.0f;
      b.cos_emit = std::cos(0.5f * kPi);
      if (pp.moves) {  // its front side as at the opening; chosen by its mean area over the steps
        tri.side = glm::dot(centre.ng, glm::cross(p1 - p0, p2 - p0)) < 0.0f ? -1.0f : 1.0f;
        const int steps = geometry.motion_steps();
        mean_area = 0.0;
        for (int k = 0; k < steps; ++k) {
          const HitRecord then = at_time(where, static_cast<float>(k) / static_cast<float>(steps - 1));
          mean_area += shape_at(then, tri.side).area / steps;
          const SceneGeometry::Corners c = geometry.corners(then);  // a deforming mesh: between steps' corners
          b.lo = glm::min(b.lo, glm::min(c.p0, glm::min(c.p1, c.p2)));
          b.hi = glm::max(b.hi, glm::max(c.p0, glm::max(c.p1, c.p2)));
        }
        if (pp.instance != RTC_INVALID_GEOMETRY_ID) {  // a placement may turn between steps: its list's sweep
          if (shutter.empty()) shutter = geometry.shutter_bounds();
          b.lo = glm::min(b.lo, shutter[list].lo);
          b.hi = glm::max(b.hi, shutter[list].hi);
        }
        b.cos_spread = -1.0f;  // turning: any way
        tri.shape = shape_at(where, tri.side);
      }
      triangles_.push_back(tri);
      bounds.push_back(b);
      const double weight = std::isfinite(mean_area) ? mean_area * (m.double_sided ? 2.0 : 1.0) : 0.0;
      if (textured) textured_triangles.emplace_back(power.size(), &m);
      power.push_back(textured ? weight : weight * le);  // textured: times its radiance, below
    }
  }
  // The textured emitters' mean radiance, four material evaluations each: in parallel (a
  // helmet whose whole body is emissive has 15,000 of them).
  tbb::parallel_for(std::size_t{0}, textured_triangles.size(), [&](std::size_t k) {
    const auto [i, m] = textured_triangles[k];
    power[i] *= textured_luminance(materials, *m, triangles_[i].texturing);
  });
  by_power_ = AliasTable(power);
  if (by_power_.empty()) {
    triangles_.clear();
    first_.clear();
  }
  for (std::size_t i = 0; i < triangles_.size(); ++i) triangles_[i].pmf = by_power_.pmf(i);
  if (triangles_.empty()) return;
  // The tree's power: what the alias table weighs by, times pi (radiance to flux); a
  // triangle the table never chooses stays out.
  for (std::size_t i = 0; i < bounds.size(); ++i)
    bounds[i].power = triangles_[i].pmf > 0.0f ? static_cast<float>(power[i] * kPi) : 0.0f;
  tree_ = LightTree(bounds, kTreeLeaf);
}

AreaLights::Shape AreaLights::shape_at(const HitRecord& where, float side) const {
  const SceneGeometry::Corners c = geometry_.corners(where);
  Shape sh{c.p0, c.p1 - c.p0, c.p2 - c.p0, vec3(0.0f), 0.0f};
  const vec3 n = glm::cross(sh.e1, sh.e2);
  const float len = glm::length(n);
  if (len > 0.0f && std::isfinite(len)) {
    sh.normal = side * n / len;
    sh.area = 0.5f * len;
  }
  return sh;
}

AreaLights::Choice AreaLights::choose(float u_select, float pick, const ShadingPlace* tree) const {
  // u_select / pick is uniform in [0, 1) below pick: the same stratified number chooses both.
  if (triangles_.empty() || !(u_select < pick)) return {};
  std::size_t i;
  float pmf;
  if (tree) {
    const LightTree::Choice c = tree_.sample(tree->p, tree->n, u_select / pick);
    if (!(c.pmf > 0.0f)) return {};  // no triangle can light the place
    i = c.light, pmf = c.pmf;
  } else {
    i = by_power_.sample(u_select / pick);
    pmf = triangles_[i].pmf;
  }
  const Triangle* tri = &triangles_[i];
  __builtin_prefetch(tri);
  __builtin_prefetch(reinterpret_cast<const char*>(tri) + 64);
  return {i, pick, pmf};
}

bool AreaLights::sample(const vec3& p, float time, const Choice& light, const vec2& u_point, AreaLightSample& s) const {
  if (light.index >= triangles_.size()) return false;
  const Triangle& tri = triangles_[light.index];
  const float pmf = light.pick * light.pmf;
  if (pmf <= 0.0f) return false;
  const Shape sh = tri.moves ? shape_at(at_time(tri.where, time), tri.side) : tri.shape;
  if (!(sh.area > 0.0f)) return false;  // a moving one where it collapses
  // Uniform point on the triangle (square-root parameterisation).
  const float su = std::sqrt(u_point.x);
  const float b1 = 1.0f - su, b2 = u_point.y * su;
  s.p = sh.p0 + b1 * sh.e1 + b2 * sh.e2;
  s.normal = sh.normal;
  const vec3 d = s.p - p;
  const float dist2 = glm::dot(d, d);
  if (!(dist2 > 0.0f)) return false;
  s.wi = d / std::sqrt(dist2);
  const float cos_light = -glm::dot(sh.normal, s.wi);
  if (!(cos_light > 0.0f || tri.double_sided)) return false;  // the back of a one-sided emitter
  const float abs_cos = std::fabs(cos_light);
  if (!(abs_cos > 0.0f)) return false;
  s.at = vec2(b1, b2);
  if (tri.textured) materials_.prefetch_emission(tri.texturing.at(b1, b2));
  s.pdf = pmf * dist2 / (sh.area * abs_cos);
  return std::isfinite(s.pdf) && s.pdf > 0.0f;
}

vec3 AreaLights::radiance(const Choice& light, const AreaLightSample& s) const {
  const Triangle& tri = triangles_[light.index];
  return tri.textured ? materials_.emission(tri.texturing.at(s.at.x, s.at.y)) : tri.radiance;
}

float AreaLights::pdf(const HitRecord& hit, const SurfaceHit& surface, const vec3& direction, float pick,
                      const ShadingPlace* tree) const {
  const auto it = first_.find(list_key(hit.geom, hit.instance));
  if (it == first_.end()) return 0.0f;
  const std::uint32_t i = it->second + hit.prim;
  if (i >= triangles_.size()) return 0.0f;
  const Triangle& tri = triangles_[i];
  const float abs_cos = std::fabs(glm::dot(surface.ng, direction));
  if (tri.pmf <= 0.0f || !(abs_cos > 0.0f)) return 0.0f;
  const float pmf = tree ? tree_.pmf(tree->p, tree->n, i) : tri.pmf;
  if (!(pmf > 0.0f)) return 0.0f;
  const float area = tri.moves ? shape_at(at_time(tri.where, hit.time), tri.side).area : tri.shape.area;
  return pick * pmf * surface.t * surface.t / (area * abs_cos);
}

}  // namespace tessera
