// SceneGeometry::shutter_bounds: where each placed triangle list can be while the shutter is
// open, as Embree moves it (renderer/geometry/motion.h): vertices linearly between motion steps, a
// moving placement by parts (translation and upper linearly, the rotation by slerp).
#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "renderer/geometry/motion.h"
#include "renderer/geometry/scene_geometry.h"

namespace tessera {
namespace {

// A mesh's box over every motion step of its vertices (in between, each vertex is on the
// segment between two steps' positions: inside).
Bounds3 own_bounds(const TriangleMesh& mesh) {
  Bounds3 b;
  for (const vec3& p : mesh.positions) b.extend(p);
  for (const MeshArray<vec3>& step : mesh.motion_positions)
    for (const vec3& p : step) b.extend(p);
  return b;
}

vec3 corner(const Bounds3& b, int i) { return {i & 1 ? b.hi.x : b.lo.x, i & 2 ? b.hi.y : b.lo.y, i & 4 ? b.hi.z : b.lo.z}; }

Bounds3 transformed(const Bounds3& b, const glm::mat4& m) {
  Bounds3 out;
  for (int i = 0; i < 8; ++i) out.extend(vec3(m * glm::vec4(corner(b, i), 1.0f)));
  return out;
}

// Where `b` can be while its placement moves from `from` to `to`. Without a turn the motion
// is affine in time (translation and upper move linearly): both ends' boxes hold it. With
// one, a point x stays within |upper x| of the translation (a rotation keeps lengths, and the
// interpolated upper's |upper x| is at most the larger end's), which moves on a straight line.
Bounds3 swept(const Bounds3& b, const glm::mat4& from, const glm::mat4& to) {
  const AffineParts p = decompose(from), q = decompose(to);
  Bounds3 out = transformed(b, from);
  out.extend(transformed(b, to));
  if (p.rotation == q.rotation || p.rotation == -q.rotation) return out;
  float reach = 0.0f;
  for (int i = 0; i < 8; ++i) reach = std::max({reach, glm::length(p.upper * corner(b, i)), glm::length(q.upper * corner(b, i))});
  reach *= 1.0f + 1e-5f;  // the float products above and Embree's
  for (const vec3& t : {p.translation, q.translation}) {
    out.extend(t - vec3(reach));
    out.extend(t + vec3(reach));
  }
  return out;
}

}  // namespace

std::vector<Bounds3> SceneGeometry::shutter_bounds() const {
  std::unordered_map<const TriangleMesh*, Bounds3> own;
  auto own_box = [&](const TriangleMesh* mesh) -> const Bounds3& {
    auto it = own.find(mesh);
    if (it == own.end()) it = own.emplace(mesh, own_bounds(*mesh)).first;
    return it->second;
  };
  std::vector<Bounds3> out;
  for (const PlacedPrimitive& p : placed_primitives()) {
    const Bounds3& box = own_box(p.mesh);
    if (box.empty() || p.instance == RTC_INVALID_GEOMETRY_ID) {  // nothing, or baked into world space
      out.push_back(box);
      continue;
    }
    const Instance& inst = scene_.instances[top_instances_[p.instance].instance];
    if (!top_instances_[p.instance].moving) {
      out.push_back(transformed(box, p.to_world));
      continue;
    }
    Bounds3 all;
    const glm::mat4* previous = &inst.object_to_world;
    for (const glm::mat4& next : inst.motion) {
      all.extend(swept(box, *previous, next));
      previous = &next;
    }
    out.push_back(all);
  }
  return out;
}

}  // namespace tessera
