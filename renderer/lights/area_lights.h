// Emissive triangles as area lights for next-event estimation: one is chosen in proportion
// to its emitted power (an alias table), or by a light tree over them from the shading point
// (by power, distance and orientation: many lights spread over a large space), then a point
// uniformly on it. A triangle that moves or deforms while the shutter is open is sampled where
// it is at the path's time, with its area then.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <vector>

#include "renderer/lights/light_tree.h"
#include "renderer/sampling/alias_table.h"
#include "renderer/materials/materials.h"
#include "renderer/geometry/scene_geometry.h"

namespace tessera {

struct AreaLightSample {
  vec3 p{0.0f};  // point on the light
  vec3 normal{0.0f};  // the light's unit geometric normal there (either side)
  vec3 wi{0.0f};  // unit direction from the shading point to p
  vec2 at{0.0f};  // the point's weights of the triangle's second and third corner
  float pdf = 0.0f;  // solid angle, at the shading point
};

class AreaLights {
 public:
  AreaLights(const SceneDescription& scene, const SceneGeometry& geometry, const MaterialTable& materials);

  bool empty() const { return triangles_.empty(); }
  std::size_t size() const { return triangles_.size(); }

  // The light tree over the triangles (leaves of up to a few triangles, chosen there by
  // power: area_lights.cpp, kTreeLeaf), built with them. Its bounds per triangle: the box of its corners, its front
  // normal as the cone's axis with emission up to 90 degrees from it (double-sided: any way),
  // power = emitted luminance x area x pi (x2 double-sided); one that moves: where it can be
  // over the shutter, any way.
  const LightTree& tree() const { return tree_; }
  // The shading point the tree chooses a light for: its position and surface normal (either
  // side). A choice by power alone does not look at it.
  struct ShadingPlace {
    vec3 p{0.0f}, n{0.0f};
  };

  // The light u_select chooses, its record prefetched: with probability `pick` one of them
  // (by power; integrator/emitter_pick.h), else none. With no light (and before a choice), an
  // index past the end. A path chooses as soon as it knows its hit, so that the record (one
  // of thousands: a cache miss) arrives while the material is evaluated.
  // `tree`: the light tree chooses for that place; null: by power.
  struct Choice {
    std::size_t index = std::numeric_limits<std::size_t>::max();
    float pick = 1.0f;  // the probability of choosing any light: a factor of the sample's pdf
    float pmf = 0.0f;  // the probability of choosing this one, once any is chosen
  };
  Choice choose(float u_select, float pick = 1.0f, const ShadingPlace* tree = nullptr) const;

  // Samples a point on the chosen light as seen from `p` at `time`; false when the sample
  // carries nothing. A textured emission's texels are prefetched: radiance() reads them, after
  // the caller has evaluated its BSDF meanwhile.
  bool sample(const vec3& p, float time, const Choice& light, const vec2& u_point, AreaLightSample& s) const;
  vec3 radiance(const Choice& light, const AreaLightSample& s) const;  // emitted towards the shading point

  // Solid-angle pdf with which sample() would have produced the hit `hit` (a point on an
  // emissive triangle at hit.time, surface.t away from the shading point along `direction`)
  // after a choice with probability `pick` of any light; `tree`: chosen by the tree for that
  // shading place (the probability its walk gives, exactly), null: by power.
  float pdf(const HitRecord& hit, const SurfaceHit& surface, const vec3& direction, float pick = 1.0f,
            const ShadingPlace* tree = nullptr) const;

 private:
  // Where a triangle is: corner, edges, front normal and area.
  struct Shape {
    vec3 p0, e1, e2;  // world space
    vec3 normal;  // unit, front side (as SurfaceHit::ng)
    float area;
  };
  // Laid out so that a light sample reads two cache lines: the first holds the shape and the
  // flags, the second the emission (texture corners or constant radiance); `where`, after them,
  // is read only for a moving triangle.
  struct alignas(64) Triangle {
    Shape shape;  // where it stands; at the shutter's opening when it moves
    float side = 1.0f;  // +1 when the front normal is along cross(e1, e2), else -1
    bool textured = false;  // emission varies: evaluate the material at each point
    bool double_sided = false;
    bool moves = false;  // moves or deforms: its shape comes from the geometry at each time
    float pmf = 0.0f;  // the probability of choosing it by power
    alignas(64) TextureCorners texturing;  // where the material's textures are read, when textured
    vec3 radiance{0.0f};  // the emission when it is constant over the triangle
    HitRecord where;  // geom, prim and instance, to evaluate the surface at a point
  };
  static_assert(offsetof(Triangle, texturing) == 64 && offsetof(Triangle, where) == 128, "two lines per sample");
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
  AliasTable by_power_;
  LightTree tree_;
  std::unordered_map<std::uint64_t, std::uint32_t> first_;  // list_key -> its first triangle
};

}  // namespace tessera
