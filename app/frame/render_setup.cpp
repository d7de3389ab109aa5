#include "app/frame/render_setup.h"

#include <chrono>

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "app/frame/auto_background.h"
#include "app/cli/exit_codes.h"
#include "scene_io/gltf_loader.h"
#include "imageio/environment_image.h"

namespace tessera {

Camera choose_camera(const SceneDescription& scene, const std::string& choice, int width, int height,
                     const Bounds3* framing) {
  if (choice.empty()) return scene.cameras.empty() ? auto_camera(framing ? *framing : scene.bounds, width, height) : scene.cameras[0];
  for (const Camera& c : scene.cameras)
    if (c.name == choice) return c;
  const bool numeric = !choice.empty() && choice.size() < 9 && std::all_of(choice.begin(), choice.end(), ::isdigit);
  if (numeric && std::stoi(choice) < static_cast<int>(scene.cameras.size())) return scene.cameras[std::stoi(choice)];
  std::string names;
  for (std::size_t i = 0; i < scene.cameras.size(); ++i)
    names += fmt::format("{}{} '{}'", i ? ", " : "", i, scene.cameras[i].name);
  throw UsageError(fmt::format("--camera {}: {} has no such camera ({})", choice, scene.source_path,
                               names.empty() ? "it has no cameras" : "it has " + names));
}

void resolve_resolution(const Camera* camera, int& width, int& height) {
  const float aspect = default_aspect(camera);
  if (width <= 0 && height <= 0) width = 960;
  if (width <= 0) width = std::max(1, static_cast<int>(std::lround(height * aspect)));
  if (height <= 0) height = std::max(1, static_cast<int>(std::lround(width / aspect)));
}

std::uint64_t emissive_triangle_count(const SceneDescription& scene, bool untextured_only) {
  std::uint64_t count = 0;
  for (const Instance& inst : scene.instances)
    for (const TriangleMesh& prim : scene.meshes[inst.mesh].primitives) {
      if (prim.material < 0) continue;
      const Material& m = scene.materials[prim.material];
      if (untextured_only && m.emissive_texture.present()) continue;
      if (m.emissive_strength > 0.0f && max_component(m.emissive_factor) > 0.0f) count += prim.triangle_count();
    }
  return count;
}

float autofocus_distance(const RenderScene& scene, const RenderCamera& camera) {
  RenderCamera pinhole = camera;
  pinhole.lens_radius = 0.0f;
  const Ray ray = pinhole.generate_ray({0.5f, 0.5f}, {0.5f, 0.5f});
  HitRecord hit;
  if (scene.geometry->intersect(ray, hit)) return hit.t * glm::dot(ray.direction, camera.forward());
  const Bounds3& b = scene.description.bounds;
  const float d = b.empty() ? 1.0f : glm::dot(b.center() - camera.position(), camera.forward());
  return d > 0.0f ? d : 1.0f;
}

MeasuredScene load_measured_scene(const std::string& path, int width, const std::string& envmap) {
  const auto start = std::chrono::steady_clock::now();
  GltfLoadResult loaded = load_gltf(path);
  MeasuredScene m;
  m.load_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  m.width = width;
  const Camera* first = loaded.scene.cameras.empty() ? nullptr : &loaded.scene.cameras[0];
  resolve_resolution(first, m.width, m.height);
  const Camera camera = choose_camera(loaded.scene, "", m.width, m.height);
  EnvironmentParams env;
  env.background = vec3(choose_auto_background(loaded.scene).black ? 0.0f : 1.0f);
  env.image_path = envmap;
  if (!envmap.empty()) env.image = read_environment_image(envmap);
  const auto build = std::chrono::steady_clock::now();
  m.scene = std::make_unique<RenderScene>(std::move(loaded.scene), env);
  m.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - build).count();
  m.camera = m.scene->camera(camera, m.width, m.height, {});
  return m;
}

}  // namespace tessera
