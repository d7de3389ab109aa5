#include "renderer/scene/render_scene.h"

#include <chrono>
#include <stdexcept>

#include "renderer/geometry/packet_check.h"
#include "renderer/geometry/render_origin.h"

namespace tessera {

EmbreeDevice::EmbreeDevice() {
  device_ = rtcNewDevice("verbose=0");
  if (!device_) throw std::runtime_error("Embree could not create a device (unsupported CPU?)");
}

EmbreeDevice::~EmbreeDevice() { rtcReleaseDevice(device_); }

namespace {

// The lights' transforms over the shutter, for those that move.
std::vector<MotionTransform> light_motions(const SceneDescription& scene) {
  std::vector<MotionTransform> out;
  for (const PunctualLight& light : scene.lights) {
    if (light.motion.empty() || scene.motion_steps < 2) {
      out.emplace_back();
      continue;
    }
    if (light.motion.size() != static_cast<std::size_t>(scene.motion_steps - 1))
      throw std::invalid_argument("light " + light.name + " does not have motion_steps - 1 motion steps");
    std::vector<glm::mat4> steps{light.light_to_world};
    steps.insert(steps.end(), light.motion.begin(), light.motion.end());
    out.emplace_back(steps);
  }
  return out;
}

// Takes `next`'s vertex arrays where they differ from `now`'s; true if they did.
bool take_vertices(TriangleMesh& now, TriangleMesh& next) {
  if (now.positions == next.positions && now.normals == next.normals && now.tangents == next.tangents &&
      now.texcoords0 == next.texcoords0 && now.texcoords1 == next.texcoords1 && now.colors == next.colors &&
      now.motion_positions == next.motion_positions && now.motion_normals == next.motion_normals &&
      now.motion_tangents == next.motion_tangents)
    return false;
  std::swap(now.positions, next.positions);
  std::swap(now.normals, next.normals);
  std::swap(now.tangents, next.tangents);
  std::swap(now.texcoords0, next.texcoords0);
  std::swap(now.texcoords1, next.texcoords1);
  std::swap(now.colors, next.colors);
  std::swap(now.motion_positions, next.motion_positions);
  std::swap(now.motion_normals, next.motion_normals);
  std::swap(now.motion_tangents, next.motion_tangents);
  return true;
}

}  // namespace

bool RenderScene::update(SceneDescription& next) {
  if (next.materials.size() != description.materials.size() || next.images.size() != description.images.size() ||
      render_origin(next) != origin || !geometry->can_update(next))
    return false;
  const auto start = std::chrono::steady_clock::now();
  move_to_render_frame(next, origin);
  // In place: the BVH, the filters and the lights keep pointers to these meshes.
  std::vector<std::vector<char>> changed_primitives(description.meshes.size());
  for (std::size_t m = 0; m < description.meshes.size(); ++m)
    for (std::size_t p = 0; p < description.meshes[m].primitives.size(); ++p)
      changed_primitives[m].push_back(take_vertices(description.meshes[m].primitives[p], next.meshes[m].primitives[p]));
  std::vector<char> changed_instances;
  for (std::size_t i = 0; i < description.instances.size(); ++i) {
    Instance &now = description.instances[i], &then = next.instances[i];
    changed_instances.push_back(now.object_to_world != then.object_to_world || now.motion != then.motion);
    now.object_to_world = then.object_to_world;
    std::swap(now.motion, then.motion);
  }
  description.cameras = std::move(next.cameras);
  description.lights = std::move(next.lights);
  light_motion = light_motions(description);
  light_tree = LightTree(description.lights);
  description.bounds = next.bounds;
  description.shutter_open = next.shutter_open;
  description.shutter_close = next.shutter_close;
  rebuilt_triangles = geometry->update(changed_primitives, changed_instances);
  bvh_build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  area_lights = std::make_unique<AreaLights>(description, *geometry, materials);
  return true;
}

RenderScene::RenderScene(SceneDescription scene, const EnvironmentParams& env)
    : origin(render_origin(scene)), description(std::move(scene)), environment(env), materials(description) {
  move_to_render_frame(description, origin);
  const auto start = std::chrono::steady_clock::now();
  geometry = std::make_unique<SceneGeometry>(description, device.get(), materials.surface_opacity());
  bvh_build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  geometry->use_packets(packets_match_single_rays(device.get(), geometry->moves()));
  area_lights = std::make_unique<AreaLights>(description, *geometry, materials);
  light_motion = light_motions(description);
  light_tree = LightTree(description.lights);
}

RenderCamera RenderScene::camera(const Camera& cam, int width, int height, const CameraParams& params) const {
  RenderCamera rc = make_camera(camera_in_render_frame(cam, origin), width, height, params);
  rc.origin = origin;
  return rc;
}

void RenderScene::check_camera(const RenderCamera& camera) const {
  if (camera.origin != origin)
    throw std::invalid_argument("a camera made for another frame than the scene's render frame (use RenderScene::camera)");
}

}  // namespace tessera
