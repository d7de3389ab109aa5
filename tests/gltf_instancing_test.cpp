// EXT_mesh_gpu_instancing: each instance at node world x T x R x S (the extension's
// specification). Expected positions are worked out by hand from that closed form; the
// quaternions are multiples of 90 degrees, so they are exact up to float rounding.
// tests/data/gpu_instancing.gltf passes the Khronos glTF-Validator with no error or warning.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

#include "renderer/scene/render_scene.h"
#include "scene_io/gltf_loader.h"
#include "scene_io/base/load_error.h"
#include "tests/test_support.h"

namespace tessera {
namespace {

// Where instance `i` puts vertex `v` of the one-triangle mesh (0,0,0) (1,0,0) (0,1,0).
glm::vec3 placed(const SceneDescription& s, int i, int v) {
  const glm::vec3 p = s.meshes.at(0).primitives.at(0).positions.at(v);
  return glm::vec3(s.instances.at(i).object_to_world * glm::vec4(p, 1.0f));
}

void expect_at(const SceneDescription& s, int i, int v, glm::vec3 expected) {
  const glm::vec3 p = placed(s, i, v);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(p[c], expected[c], 2e-5f) << "instance " << i << " vertex " << v;
}

TEST(GltfInstancing, EachInstanceAtNodeWorldTimesTRS) {
  const GltfLoadResult r = load_gltf(test::data_path("gpu_instancing.gltf"));
  const SceneDescription& s = r.scene;
  EXPECT_TRUE(r.warnings.empty());
  ASSERT_EQ(s.meshes.size(), 1u);  // stored once, placed five times
  ASSERT_EQ(s.instances.size(), 5u);
  // Node "float": world T(0,0,-5) S(2). Instance 0: T(1,0,0).
  expect_at(s, 0, 0, {2, 0, -5});
  expect_at(s, 0, 1, {4, 0, -5});
  // Instance 1: T(0,2,0) Rz(90) S(2): (1,0,0) -> (0,2,0) + (0,2,0), then x2 and -5 in z.
  expect_at(s, 1, 1, {0, 8, -5});
  expect_at(s, 1, 2, {-4, 4, -5});
  // Instance 2: T(0,0,3) Rx(180) S(1,3,1): (0,1,0) -> (0,-3,0) -> (0,-3,3) -> (0,-6,1).
  expect_at(s, 2, 2, {0, -6, 1});
  expect_at(s, 2, 1, {2, 0, 1});
  // Node "quantized": world T(0,10,0); SHORT translations, normalized SHORT rotations,
  // UNSIGNED_BYTE scales. Instance 0: T(4,0,0), rotation (0,0,0,32767) = identity.
  expect_at(s, 3, 1, {5, 10, 0});
  // Instance 1: T(-4,0,0), (0,23170,0,23170) = Ry(90) once normalized, S(2).
  expect_at(s, 4, 1, {-4, 10, -2});
  expect_at(s, 4, 2, {-4, 12, 0});
  EXPECT_EQ(s.instances[4].node_name, "quantized");
  EXPECT_NEAR(s.bounds.lo.y, -6.0f, 1e-5f);
  EXPECT_NEAR(s.bounds.hi.y, 12.0f, 1e-5f);
}

// `n` instances of the unit triangle, instance i at (3i, 0, 0) turned by 90 i degrees about z.
std::vector<std::uint8_t> row_of_triangles(int n) {
  std::vector<float> f = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  for (int i = 0; i < n; ++i) f.insert(f.end(), {3.0f * i, 0, 0});
  const float h = std::sqrt(0.5f);
  const float quarter[4][4] = {{0, 0, 0, 1}, {0, 0, h, h}, {0, 0, 1, 0}, {0, 0, h, -h}};
  for (int i = 0; i < n; ++i) f.insert(f.end(), quarter[i % 4], quarter[i % 4] + 4);
  std::vector<std::uint8_t> bin(f.size() * 4);
  std::memcpy(bin.data(), f.data(), bin.size());
  const std::string json =
      R"({"asset":{"version":"2.0"},"extensionsUsed":["EXT_mesh_gpu_instancing"],"scenes":[{"nodes":[0]}],)"
      R"("nodes":[{"mesh":0,"extensions":{"EXT_mesh_gpu_instancing":{"attributes":{"TRANSLATION":1,"ROTATION":2}}}}],)"
      R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
      R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},)" +
      fmt::format(R"({{"bufferView":1,"componentType":5126,"count":{0},"type":"VEC3"}},)"
                  R"({{"bufferView":2,"componentType":5126,"count":{0},"type":"VEC4"}}],)"
                  R"("bufferViews":[{{"buffer":0,"byteLength":36}},{{"buffer":0,"byteOffset":36,"byteLength":{1}}},)"
                  R"({{"buffer":0,"byteOffset":{2},"byteLength":{3}}}],)",
                  n, 12 * n, 36 + 12 * n, 16 * n) +
      R"("buffers":[{"byteLength":)" + std::to_string(bin.size()) +
      R"(,"uri":"data:application/octet-stream;base64,)" + test::base64(bin) + "\"}]}";
  return {json.begin(), json.end()};
}

TEST(GltfInstancing, RaysHitEveryInstanceWhereTheClosedFormPlacesIt) {
  const int n = 40;
  RenderScene rs(load_gltf_from_memory(row_of_triangles(n), "row.gltf", ".").scene, {});
  for (int i = 0; i < n; ++i) {
    // The triangle's centroid (1/3, 1/3) turned by 90 i degrees, then moved to (3i, 0, 0).
    const float a = glm::radians(90.0f * (i % 4));
    const glm::vec3 c(3.0f * i + (std::cos(a) - std::sin(a)) / 3.0f, (std::sin(a) + std::cos(a)) / 3.0f, 0.0f);
    Ray ray{c + glm::vec3(0, 0, 2), glm::vec3(0, 0, -1)};
    HitRecord hit;
    ASSERT_TRUE(rs.geometry->intersect(ray, hit)) << "instance " << i;
    EXPECT_NEAR(hit.t, 2.0f, 1e-5f);
    // The centroid mirrored through the instance's origin is outside its triangle.
    Ray miss{glm::vec3(6.0f * i, 0, 0) - c + glm::vec3(0, 0, 2), glm::vec3(0, 0, -1)};
    EXPECT_FALSE(rs.geometry->intersect(miss, hit)) << "instance " << i;
  }
}

TEST(GltfInstancing, MemoryIsFlatInTheNumberOfInstances) {
  for (int n : {1, 10, 10000}) {
    RenderScene rs(load_gltf_from_memory(row_of_triangles(n), "row.gltf", ".").scene, {});
    EXPECT_EQ(rs.geometry->unique_triangles(), 1u) << n;  // the mesh's triangles are stored once
    EXPECT_EQ(rs.geometry->instanced_triangles(), static_cast<std::uint64_t>(n));
  }
}

TEST(GltfInstancing, AttributesOfDifferentCountsAreRefused) {
  std::vector<std::uint8_t> bytes = row_of_triangles(4);
  std::string json(bytes.begin(), bytes.end());
  json.replace(json.find(R"("count":4,"type":"VEC4")"), 9, R"("count":3)");
  try {
    load_gltf_from_memory({json.begin(), json.end()}, "counts.gltf", ".");
    ADD_FAILURE() << "loaded";
  } catch (const SceneLoadError& e) {
    EXPECT_EQ(e.problem(), "node 0 has EXT_mesh_gpu_instancing attributes of different counts (4 and 3); "
                           "they must be equal");
  }
}

}  // namespace
}  // namespace tessera
