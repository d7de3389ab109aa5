#include "tests/scene_builders.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <glm/gtc/matrix_transform.hpp>

namespace tessera::test {

TriangleMesh make_quad(glm::vec3 center, glm::vec3 u, glm::vec3 v, int material) {
  TriangleMesh m;
  m.positions = {center - u - v, center + u - v, center + u + v, center - u + v};
  const glm::vec3 n = glm::normalize(glm::cross(u, v));
  m.normals.assign(4, n);
  m.texcoords0 = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  m.indices = {0, 1, 2, 0, 2, 3};
  m.material = material;
  return m;
}

TriangleMesh make_sphere(glm::vec3 center, float radius, int subdivisions, int material, bool inward, bool smooth) {
  const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
  std::vector<glm::vec3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                              {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (auto& p : v) p = glm::normalize(p);
  MeshArray<std::uint32_t> f = {0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4,
                                  11, 10, 2, 10, 7, 6, 7, 1, 8, 3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8,
                                  3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7, 9, 8, 1};
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      v.push_back(glm::normalize(v[a] + v[b]));
      return mid[key] = static_cast<std::uint32_t>(v.size() - 1);
    };
    MeshArray<std::uint32_t> g;
    for (std::size_t i = 0; i < f.size(); i += 3) {
      const std::uint32_t a = f[i], b = f[i + 1], c = f[i + 2];
      const std::uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      g.insert(g.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    f = std::move(g);
  }
  TriangleMesh m;
  for (const auto& p : v) {
    m.positions.push_back(center + radius * p);
    if (smooth) m.normals.push_back(inward ? -p : p);
  }
  if (inward)
    for (std::size_t i = 0; i < f.size(); i += 3) std::swap(f[i + 1], f[i + 2]);
  m.indices = std::move(f);
  m.material = material;
  return m;
}

int add_material(SceneDescription& scene, const Material& material) {
  scene.materials.push_back(material);
  return static_cast<int>(scene.materials.size() - 1);
}

int add_mesh(SceneDescription& scene, TriangleMesh mesh, const std::vector<glm::mat4>& placements) {
  Mesh m;
  m.primitives.push_back(std::move(mesh));
  scene.meshes.push_back(std::move(m));
  const int index = static_cast<int>(scene.meshes.size() - 1);
  for (const glm::mat4& t : placements) {
    scene.instances.push_back({index, t, "", {}});
    for (const glm::vec3& p : scene.meshes[index].primitives[0].positions)
      scene.bounds.extend(glm::vec3(t * glm::vec4(p, 1.0f)));
  }
  return index;
}

Material diffuse(glm::vec3 albedo) {
  Material m;
  m.base_color_factor = glm::vec4(albedo, 1.0f);
  m.metallic_factor = 0.0f;
  m.specular_factor = 0.0f;  // KHR_materials_specular 0: no specular layer, pure Lambert
  return m;
}

Material emitter(glm::vec3 radiance) {
  Material m = diffuse(glm::vec3(0.0f));
  m.emissive_factor = radiance;
  return m;
}

Camera look_at(glm::vec3 eye, glm::vec3 target, float yfov_degrees) {
  Camera c;
  c.camera_to_world = glm::inverse(glm::lookAtRH(eye, target, glm::vec3(0, 1, 0)));
  c.yfov = glm::radians(yfov_degrees);
  return c;
}

SceneDescription lit_floor_and_sphere() {
  SceneDescription d;
  const int white = add_material(d, diffuse(glm::vec3(0.7f)));
  add_mesh(d, make_quad({0, -1, 0}, {2, 0, 0}, {0, 0, -2}, white));
  add_mesh(d, make_sphere({0, -0.5f, 0}, 0.5f, 2, white));
  add_mesh(d, make_quad({0, 1, 0}, {0.3f, 0, 0}, {0, 0, 0.3f}, add_material(d, emitter(glm::vec3(5)))));
  return d;
}

double floor_under_square_emitter(double a, double h, double le, double albedo) {
  auto corner = [](double x, double y) {
    return (x / std::sqrt(1 + x * x) * std::atan(y / std::sqrt(1 + x * x)) +
            y / std::sqrt(1 + y * y) * std::atan(x / std::sqrt(1 + y * y))) / (2 * M_PI);
  };
  return albedo * le * 4 * corner(a / h, a / h);
}

}  // namespace tessera::test
