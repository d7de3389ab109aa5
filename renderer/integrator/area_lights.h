// Emissive triangles as area lights for next-event estimation: one is chosen in proportion
// to its emitted power, then a point uniformly on it.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "renderer/distribution.h"
#include "renderer/integrator/materials.h"
#include "renderer/scene_geometry.h"

namespace tessera {

struct AreaLightSample {
  vec3 p{0.0f};  // point on the light
  vec3 wi{0.0f};  // unit direction from the shading point to p
  float distance = 0.0f;
  vec3 radiance{0.0f};  // emitted towards the shading point
  float pdf = 0.0f;  // solid angle, at the shading point
};

class AreaLights {
 public:
  AreaLights(const SceneDescription& scene, const SceneGeometry& geometry, const MaterialTable& materials);

  bool empty() const { return triangles_.empty(); }
  std::size_t size() const { return triangles_.size(); }

  // Samples a light point as seen from `p`; false when the sample carries nothing.
  bool sample(const vec3& p, float u_select, const vec2& u_point, AreaLightSample& s) const;

  // Solid-angle pdf with which sample() would have produced the hit `hit` (a point on an
  // emissive triangle, `distance` away from the shading point along `direction`).
  float pdf(const HitRecord& hit, const SurfaceHit& surface, const vec3& direction) const;

 private:
  struct Triangle {
    HitRecord where;  // geom, prim and instance, to evaluate the surface at a point
    vec3 p0, e1, e2;  // world space
    vec3 normal;  // unit, front side (as SurfaceHit::ng)
    float area;
    vec3 radiance;  // the emission when it is constant over the triangle
    bool textured;  // emission varies: evaluate the material at each point
    bool double_sided;
  };
  // (top-level id, geometry within it) of a triangle list: instance id and geometry for an
  // instanced mesh, the top-level geometry for a baked one.
  static std::uint64_t list_key(std::uint32_t geom, std::uint32_t instance) {
    return instance == RTC_INVALID_GEOMETRY_ID ? geom : (std::uint64_t(instance) << 32 | geom) | (1ull << 63);
  }

  const SceneGeometry& geometry_;
  const MaterialTable& materials_;
  std::vector<Triangle> triangles_;
  Distribution1D by_power_;
  std::unordered_map<std::uint64_t, std::uint32_t> first_;  // list_key -> its first triangle
};

}  // namespace tessera
