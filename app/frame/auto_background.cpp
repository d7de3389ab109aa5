#include "app/frame/auto_background.h"

#include <fmt/format.h>

#include "renderer/util/math.h"

namespace tessera {

namespace {


// Emission through a texture is mostly decoration (screens, glowing details): not counted.
double emitted_radiance(const Material& m) {
  if (m.emissive_texture.present() || !(m.emissive_strength > 0.0f)) return 0.0;
  return static_cast<double>(luminance(m.emissive_factor)) * m.emissive_strength * (m.double_sided ? 2.0 : 1.0);
}

double placed_area(const TriangleMesh& prim, const glm::mat4& to_world) {
  double area = 0.0;
  for (std::size_t t = 0; t + 2 < prim.indices.size(); t += 3) {
    const glm::vec3 a(to_world * glm::vec4(prim.positions[prim.indices[t]], 1.0f));
    const glm::vec3 b(to_world * glm::vec4(prim.positions[prim.indices[t + 1]], 1.0f));
    const glm::vec3 c(to_world * glm::vec4(prim.positions[prim.indices[t + 2]], 1.0f));
    area += 0.5 * static_cast<double>(glm::length(glm::cross(b - a, c - a)));
  }
  return area;
}

}  // namespace

double white_background_power(const SceneDescription& scene) {
  if (scene.bounds.empty()) return 0.0;
  const glm::dvec3 e = glm::dvec3(scene.bounds.hi) - glm::dvec3(scene.bounds.lo);
  return kPi * 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
}

double untextured_emitter_power(const SceneDescription& scene) {
  double power = 0.0;
  for (const Instance& inst : scene.instances)
    for (const TriangleMesh& prim : scene.meshes[inst.mesh].primitives) {
      if (prim.material < 0) continue;
      const double radiance = emitted_radiance(scene.materials[prim.material]);
      if (radiance > 0.0) power += kPi * radiance * placed_area(prim, inst.object_to_world);
    }
  return power;
}

AutoBackground choose_auto_background(const SceneDescription& scene) {
  if (!scene.lights.empty())
    return {true, fmt::format("{} punctual light{}", scene.lights.size(), scene.lights.size() == 1 ? "" : "s")};
  const double emitted = untextured_emitter_power(scene);
  if (emitted <= 0.0) return {false, "no lights"};
  const double white = white_background_power(scene);
  if (!(white > 0.0)) return {true, "emitters on a flat scene"};
  const double share = emitted / white;
  return {share >= kAutoBlackShare,
          fmt::format("emitters give {:.3g}% of the power a white background would", 100.0 * share)};
}

}  // namespace tessera
