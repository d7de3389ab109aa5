#include "renderer/geometry/packet_check.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "renderer/sampling/sampler.h"

namespace tessera {
namespace {

// A UV sphere of radius 1: many shared edges and vertices, as tessellated models have.
TriangleMesh uv_sphere(int rings, int segments) {
  TriangleMesh m;
  for (int r = 0; r <= rings; ++r)
    for (int s = 0; s <= segments; ++s) {
      const float theta = kPi * r / rings, phi = 2.0f * kPi * s / segments;
      const vec3 p(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
      m.positions.push_back(p);
      m.normals.push_back(p);
    }
  const auto at = [&](int r, int s) { return static_cast<std::uint32_t>(r * (segments + 1) + s); };
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s)
      m.indices.insert(m.indices.end(), {at(r, s), at(r + 1, s), at(r + 1, s + 1), at(r, s), at(r + 1, s + 1), at(r, s + 1)});
  return m;
}

// The sphere baked into world space (one still placement) and a second mesh of it placed
// twice: the ways SceneGeometry hands still triangles to Embree. With motion, also a third
// placement of the second, moving, and a deforming copy of the first.
SceneDescription check_scene(bool motion) {
  SceneDescription d;
  d.motion_steps = motion ? 2 : 1;
  const Mesh sphere{"sphere", {uv_sphere(48, 96)}};
  d.meshes = {sphere, sphere};
  // Placements as an animation makes them: turned and moved along every axis.
  const auto at = [](float x, float y, float z, float degrees) {
    return glm::rotate(glm::translate(glm::mat4(1.0f), vec3(x, y, z)), glm::radians(degrees), vec3(0.3f, 1.0f, 0.2f));
  };
  d.instances = {{0, at(0.0f, 0.0f, 0.0f, 0.0f), "", {}},
                 {1, at(-2.2f, 0.13f, 0.31f, 17.0f), "", {}},
                 {1, at(-4.4f, -0.21f, -0.5f, 41.0f), "", {}}};
  if (motion) {
    d.instances.push_back({1, at(2.2f, -0.37f, 0.83f, -11.0f), "", {at(2.31f, 0.29f, 0.77f, 23.0f)}});
    Mesh deforming = sphere;
    TriangleMesh& m = deforming.primitives[0];
    m.motion_positions = {m.positions};
    for (vec3& p : m.motion_positions[0]) p = p * vec3(1.13f, 0.91f, 1.07f) + vec3(0.07f, 0.11f, -0.05f);
    d.meshes.push_back(deforming);
    d.instances.push_back({2, at(4.4f, 0.19f, -0.23f, 7.0f), "", {}});
  }
  return d;
}

// Whether every packet of the check scene's camera rays finds the single rays' hits.
bool agree(RTCDevice device, bool motion) {
  const SceneDescription scene = check_scene(motion);
  SceneGeometry g(scene, device);
  g.use_packets(true);
  constexpr int N = SceneGeometry::kPacketSize, kW = 64, kH = 16;
  const vec3 eye(0.1f, 0.05f, 9.0f);
  for (int py = 0; py < kH; ++py)
    for (int px = 0; px < kW; ++px) {
      // A pixel's samples: jittered directions through it, each at its own time.
      Sampler rng(SamplerKind::independent, px, py, 0, 0x9ac3);
      Ray rays[N];
      for (Ray& r : rays) {
        const vec3 u = rng.next3();
        const vec3 target((px + u.x) / kW * 11.2f - 5.6f, 1.4f - (py + u.y) / kH * 2.8f, 0.0f);
        r = Ray{eye, glm::normalize(target - eye)};
        r.time = u.z;
      }
      if (packet_differences(g, rays, N) > 0) return false;
    }
  return true;
}

}  // namespace

int packet_differences(const SceneGeometry& g, const Ray* rays, int n, int* hits) {
  ClosestHit packet[SceneGeometry::kPacketSize];
  vec3 normals[SceneGeometry::kPacketSize];
  g.intersect_packet(rays, n, packet, normals);
  int differ = 0;
  for (int i = 0; i < n; ++i) {
    HitRecord single;
    vec3 ng;
    const bool found = g.intersect(rays[i], single, &ng);
    if (hits) *hits += found;
    const HitRecord& h = packet[i].hit;
    const bool same = packet[i].found == found &&
                      (!found || (same_bits(h.t, single.t) && same_bits(h.u, single.u) && same_bits(h.v, single.v) &&
                                  h.geom == single.geom && h.prim == single.prim && h.instance == single.instance &&
                                  same_bits(normals[i].x, ng.x) && same_bits(normals[i].y, ng.y) &&
                                  same_bits(normals[i].z, ng.z)));
    differ += !same;
  }
  return differ;
}

bool packets_match_single_rays(RTCDevice device, bool scene_moves) {
  static const bool native = rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED) != 0;
  if (!native) return false;
  static const bool still = agree(device, false);
  if (!still || !scene_moves) return still;
  static const bool moving = agree(device, true);  // checked only when a scene moves
  return moving;
}

}  // namespace tessera
