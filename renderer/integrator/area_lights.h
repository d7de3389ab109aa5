// Emissive triangles as area lights for next-event estimation: one is chosen in proportion
// to its emitted power, then a point uniformly on it. A triangle that moves or deforms while
// the shutter is open is sampled where it is at the path's time, with its area then.
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

  // Samples a light point as seen from `p` at `time`; false when the sample carries nothing.
  bool sample(const vec3& p, float time, float u_select, const vec2& u_point, AreaLightSample& s) const;

  // Solid-angle pdf with which sample() would have produced the hit `hit` (a point on an
  // emissive triangle at hit.time, surface.t away from the shading point along `direction`).
  float pdf(const HitRecord& hit, const SurfaceHit& surface, const vec3& direction) const;

 private:
  // Where a triangle is: corner, edges, front normal and area.
  struct Shape {
    vec3 p0, e1, e2;  // world space
    vec3 normal;  // unit, front side (as SurfaceHit::ng)
    float area;
  };
  struct Triangle {
    HitRecord where;  // geom, prim and instance, to evaluate the surface at a point
    Shape shape;  // where it stands; at the shutter's opening when it moves
    vec3 radiance;  // the emission when it is constant over the triangle
    bool textured;  // emission varies: evaluate the material at each point
    TextureCorners texturing;  // where the material's textures are read, when textured
    bool double_sided;
    bool moves;  // moves or deforms: its shape comes from the geometry at each time
    float side;  // +1 when the front normal is along cross(e1, e2), else -1
  };
  // The shape of triangle `where` at where.time (area 0 where it collapses), front by `side`.
  Shape shape_at(const HitRecord& where, float side) const;
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
