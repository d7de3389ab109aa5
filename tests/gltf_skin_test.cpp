// glTF skins (scene_io/nodes/gltf_skin.*, the loader): vertices where the joint-matrix blend puts
// them, computed by hand from SimpleSkin's data, and the rules around it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "scene_io/gltf_loader.h"
#include "scene_io/base/load_error.h"
#include "tests/test_support.h"

namespace tessera {
namespace {

TriangleMesh skinned_mesh(const SceneDescription& s) {
  EXPECT_EQ(s.instances.size(), 1u);
  return s.meshes.at(s.instances.at(0).mesh).primitives.at(0);
}

void expect_near(const glm::vec3& got, const glm::vec3& want, float tolerance, const char* what) {
  EXPECT_NEAR(got.x, want.x, tolerance) << what;
  EXPECT_NEAR(got.y, want.y, tolerance) << what;
  EXPECT_NEAR(got.z, want.z, tolerance) << what;
}

// SimpleSkin: a strip of 10 vertices, x = +-0.5, y = 0, 0.5 .. 2. Joint 0 (node 1) is the
// origin; joint 1 (node 2) sits at (0, 1, 0) and its rotation about z is animated (0 s: 0,
// 0.5 s: 45 degrees, 1 s: 90 degrees, keys (0, 0, 0.383, 0.924) and (0, 0, 0.707, 0.707)).
// The inverse bind matrices are the identity and a translation by (0, -1, 0), so joint 1's
// matrix turns the strip about (0, 1, 0). Vertex weights (joint 0, joint 1): y = 0: (1, 0),
// 0.5: (0.75, 0.25), 1: (0.5, 0.5), 1.5: (0.25, 0.75), 2: (0, 1).
glm::vec3 turned(glm::vec3 v, float degrees) {  // about (0, 1, 0), counter-clockwise in xy
  const float a = glm::radians(degrees), c = std::cos(a), s = std::sin(a);
  const glm::vec3 d = v - glm::vec3(0, 1, 0);
  return glm::vec3(0, 1, 0) + glm::vec3(c * d.x - s * d.y, s * d.x + c * d.y, d.z);
}

TEST(GltfSkin, SimpleSkinVerticesAreTheJointBlend) {
  const std::string path = test::scene_path("khronos/SimpleSkin/glTF/SimpleSkin.gltf");
  struct Case { float time, degrees; };
  // 45.01: the keys are rounded to 3 digits (2 atan(0.383 / 0.924)).
  for (const Case c : {Case{0.0f, 0.0f}, Case{0.5f, 45.01f}, Case{1.0f, 90.0f}, Case{0.25f, 22.5f}}) {
    const TriangleMesh m = skinned_mesh(load_gltf(path, {"", "", "", c.time}).scene);
    ASSERT_EQ(m.positions.size(), 10u);
    const float w1[5] = {0.0f, 0.25f, 0.5f, 0.75f, 1.0f};  // joint 1's weight by row
    for (int v = 0; v < 10; ++v) {
      const glm::vec3 rest(v % 2 ? 0.5f : -0.5f, 0.5f * (v / 2), 0.0f);
      const glm::vec3 want = (1.0f - w1[v / 2]) * rest + w1[v / 2] * turned(rest, c.degrees);
      expect_near(m.positions[v], want, 2e-3f, ("vertex " + std::to_string(v)).c_str());
    }
  }
  // By hand at 90 degrees: the tip (-0.5, 2) turns to (-1, 0.5); the middle row (weights 1/2)
  // goes to the midpoint of (-0.5, 1) and (0, 0.5).
  const TriangleMesh m = skinned_mesh(load_gltf(path, {"", "", "", 1.0f}).scene);
  expect_near(m.positions[8], {-1.0f, 0.5f, 0.0f}, 1e-5f, "tip");
  expect_near(m.positions[4], {-0.25f, 0.75f, 0.0f}, 1e-5f, "middle");
  expect_near(m.positions[0], {-0.5f, 0.0f, 0.0f}, 0.0f, "root");
}

// Without animation the skin is in its bind pose: joint matrices are world x inverse bind =
// identity for both joints, so the vertices are as stored.
TEST(GltfSkin, BindPoseLeavesTheMeshAsStored) {
  const std::string path = test::scene_path("khronos/SimpleSkin/glTF/SimpleSkin.gltf");
  const TriangleMesh m = skinned_mesh(load_gltf(path, {"", "", "none"}).scene);
  for (int v = 0; v < 10; ++v)
    expect_near(m.positions[v], {v % 2 ? 0.5f : -0.5f, 0.5f * (v / 2), 0.0f}, 0.0f, "vertex");
}

// A triangle with two JOINTS/WEIGHTS sets: 1/4 on joint 0 (node 1, at (2, 0, 0)) in set 0 and
// 3/4 on joint 1 (node 2, at (0, 3, 0)) in set 1, identity inverse binds: every vertex moves by
// 1/4 (2, 0, 0) + 3/4 (0, 3, 0) = (0.5, 2.25, 0). The mesh node's own translation (9, 9, 9) is
// ignored, as the specification says.
std::vector<std::uint8_t> two_set_gltf(float weight0, const std::string& extra_skin = "") {
  std::vector<std::uint8_t> bin;
  auto put = [&](const void* data, std::size_t n) {
    const auto* b = static_cast<const std::uint8_t*>(data);
    bin.insert(bin.end(), b, b + n);
  };
  const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::uint8_t joints0[12] = {0}, joints1[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
  float weights0[12] = {0}, weights1[12] = {0};
  for (int v = 0; v < 3; ++v) weights0[4 * v] = weight0, weights1[4 * v] = 1.0f - weight0;
  put(positions, 36);
  put(joints0, 12);
  put(joints1, 12);
  put(weights0, 48);
  put(weights1, 48);
  const std::string json =
      R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[0,1]}],)"
      R"("nodes":[{"mesh":0,"skin":0,"translation":[9,9,9]},{"translation":[2,0,0],"children":[2]},)"
      R"({"translation":[-2,3,0]}],)"  // node 2 at (0, 3, 0): the joints' common root is node 1
      R"("skins":[{"joints":[1,2])" + extra_skin + R"(}],)"
      R"("meshes":[{"primitives":[{"attributes":{"POSITION":0,"JOINTS_0":1,"JOINTS_1":2,"WEIGHTS_0":3,"WEIGHTS_1":4}}]}],)"
      R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},)"
      R"({"bufferView":1,"componentType":5121,"count":3,"type":"VEC4"},)"
      R"({"bufferView":2,"componentType":5121,"count":3,"type":"VEC4"},)"
      R"({"bufferView":3,"componentType":5126,"count":3,"type":"VEC4"},)"
      R"({"bufferView":4,"componentType":5126,"count":3,"type":"VEC4"}],)"
      R"("bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":12},)"
      R"({"buffer":0,"byteOffset":48,"byteLength":12},{"buffer":0,"byteOffset":60,"byteLength":48},)"
      R"({"buffer":0,"byteOffset":108,"byteLength":48}],)"
      R"("buffers":[{"byteLength":156,"uri":"data:application/octet-stream;base64,)" + test::base64(bin) + "\"}]}";
  return {json.begin(), json.end()};
}

TEST(GltfSkin, EveryJointsAndWeightsSetCounts) {
  const SceneDescription s = load_gltf_from_memory(two_set_gltf(0.25f), "two_sets.gltf", ".").scene;
  const TriangleMesh m = skinned_mesh(s);
  expect_near(m.positions[0], {0.5f, 2.25f, 0.0f}, 1e-6f, "vertex 0");
  expect_near(m.positions[1], {1.5f, 2.25f, 0.0f}, 1e-6f, "vertex 1");
  expect_near(m.positions[2], {0.5f, 3.25f, 0.0f}, 1e-6f, "vertex 2");
  EXPECT_EQ(s.instances[0].object_to_world, glm::mat4(1.0f));
  EXPECT_EQ(s.bounds.lo, glm::vec3(0.5f, 2.25f, 0.0f));
}

TEST(GltfSkin, BadSkinsAreNamed) {
  auto problem = [](const std::vector<std::uint8_t>& bytes) {
    try {
      load_gltf_from_memory(bytes, "skin.gltf", ".");
    } catch (const SceneLoadError& e) {
      return std::string(e.what());
    }
    return std::string("loaded");
  };
  EXPECT_EQ(problem(two_set_gltf(-0.5f)), "skin.gltf: WEIGHTS_0 of mesh 0 primitive 0 has weight -0.5 at vertex 0");
  EXPECT_EQ(problem(two_set_gltf(0.25f, R"(,"skeleton":7)")), "skin.gltf: skin 0 has skeleton node 7, but the file has 3 nodes");
  EXPECT_EQ(problem(two_set_gltf(0.25f, R"(,"inverseBindMatrices":0)")),
            "skin.gltf: accessor 0 (inverseBindMatrices of skin 0) is not MAT4");
}

}  // namespace
}  // namespace tessera
