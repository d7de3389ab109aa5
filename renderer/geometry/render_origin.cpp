#include "renderer/geometry/render_origin.h"

#include <cmath>

namespace tessera {
namespace {

void move(glm::mat4& m, const vec3& origin) { m[3] -= glm::vec4(origin, 0.0f); }

void move_all(glm::mat4& m, std::vector<glm::mat4>& steps, const vec3& origin) {
  move(m, origin);
  for (glm::mat4& s : steps) move(s, origin);
}

}  // namespace

vec3 render_origin(const SceneDescription& scene) {
  const Bounds3& b = scene.bounds;
  if (b.empty() || !(b.reach() > kFarForItsSize * b.longest_side())) return vec3(0.0f);
  if (!scene.animated) return b.center();
  const float cell = std::exp2(std::ceil(std::log2(kAnimatedCell * b.longest_side())));
  return cell > 0.0f && std::isfinite(cell) ? glm::round(b.center() / cell) * cell : b.center();
}

void move_to_render_frame(SceneDescription& scene, const vec3& origin) {
  if (origin == vec3(0.0f)) return;
  for (Instance& instance : scene.instances) move_all(instance.object_to_world, instance.motion, origin);
  for (Camera& camera : scene.cameras) move_all(camera.camera_to_world, camera.motion, origin);
  for (PunctualLight& light : scene.lights) {
    light.position -= origin;
    move_all(light.light_to_world, light.motion, origin);
  }
  if (!scene.bounds.empty()) scene.bounds = {scene.bounds.lo - origin, scene.bounds.hi - origin};
}

Camera camera_in_render_frame(Camera camera, const vec3& origin) {
  move_all(camera.camera_to_world, camera.motion, origin);
  return camera;
}

}  // namespace tessera
