// Files the Khronos glTF-Validator (2.0.0-dev.3.10) calls valid load, with the warnings the
// policy in docs/reliability.md gives: tests/data/conformance/ holds them, each checked with
// tools/gltf-validate.js (0 errors; the warnings it reports are named per test). Their used
// counterparts, which the policy refuses, are in tests/data/malformed/.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "scene_io/gltf_loader.h"
#include "tests/test_support.h"

namespace tessera {
namespace {

GltfLoadResult load(const std::string& name) { return load_gltf(test::data_path("conformance/" + name)); }

std::uint64_t triangles(const SceneDescription& s) {
  std::uint64_t n = 0;
  for (const Instance& inst : s.instances)
    for (const TriangleMesh& p : s.meshes.at(inst.mesh).primitives) n += p.triangle_count();
  return n;
}

TEST(GltfConformance, UnusedBufferWithoutUriInGltf) {
  const GltfLoadResult r = load("unused_buffer_without_uri.gltf");  // validator: no warning
  EXPECT_EQ(triangles(r.scene), 1u);
  EXPECT_EQ(r.warnings, std::vector<std::string>{});
}

TEST(GltfConformance, GlbBufferOtherThanTheFirstWithoutUri) {
  const GltfLoadResult r = load("glb_placeholder_buffer.glb");  // buffer 1: 1024 bytes, no uri
  EXPECT_EQ(triangles(r.scene), 1u);
  EXPECT_EQ(r.scene.bounds.hi, glm::vec3(1, 1, 0));
  EXPECT_EQ(r.warnings, std::vector<std::string>{});
}

TEST(GltfConformance, GlbTrailingByteIsIgnoredWithAWarning) {
  const GltfLoadResult r = load("glb_trailing_byte.glb");  // validator: warning GLB_EXTRA_DATA
  EXPECT_EQ(triangles(r.scene), 1u);
  EXPECT_EQ(r.warnings, std::vector<std::string>{"1 byte after the end its binary glTF header gives are ignored"});
}

TEST(GltfConformance, IndicesWithoutBufferViewAreZerosBarSparseOnes) {
  const GltfLoadResult r = load("indices_without_bufferview.gltf");
  const Mesh& mesh = r.scene.meshes.at(0);
  ASSERT_EQ(mesh.primitives.size(), 2u);
  EXPECT_EQ(mesh.primitives[0].indices, (std::vector<std::uint32_t>{0, 0, 0}));  // all zeros
  EXPECT_EQ(mesh.primitives[1].indices, (std::vector<std::uint32_t>{0, 1, 2}));  // sparse 1, 2 at 1, 2
}

TEST(GltfConformance, UnusedObjectsOfEveryKindLoadInvalidOnesWithAWarning) {
  // Validator: warnings VALUE_NOT_IN_LIST (accessor 1 type VEC5), IMAGE_UNRECOGNIZED_FORMAT.
  const GltfLoadResult r = load("unused_objects.gltf");
  EXPECT_EQ(triangles(r.scene), 1u);  // scene 0 places mesh 0 once; scene 1, mesh 1 unused
  EXPECT_EQ(r.warnings, (std::vector<std::string>{
                            "ignored, as the scene does not use it: accessor 1 has unknown type 'VEC5'",
                            "ignored, as the scene does not use it: image 0 (bufferView 2) could not be decoded: "
                            "it is not a PNG, JPEG or WebP image"}));
}

TEST(GltfConformance, InvalidObjectsTheSceneDoesNotUseAreWarnings) {
  // Validator: errors INVALID_INDEX (material 0's baseColorTexture index -1), TYPE_MISMATCH
  // (mesh 1's primitives is an object) and ACCESSOR_INVALID_FLOAT (accessor 1 holds a NaN).
  // Used, each refuses the file (tests/data/malformed/texture_index_negative.gltf,
  // primitives_not_array.gltf; GltfLoader.NonFinitePositionsAreRejected).
  const GltfLoadResult r = load("unused_invalid_objects.gltf");
  EXPECT_EQ(triangles(r.scene), 1u);
  EXPECT_EQ(r.warnings, (std::vector<std::string>{
                            "ignored, as the scene does not use it: material 0 has baseColorTexture index -1, which "
                            "names no texture",
                            "ignored, as the scene does not use it: mesh 1 has a \"primitives\" that is not an array; "
                            "glTF requires an array of at least one primitive",
                            "ignored, as the scene does not use it: accessor 1 (unused) holds NaN at element 0"}));
}

TEST(GltfConformance, InfoListsTheWarnings) {
  const std::string path = test::data_path("conformance/unused_invalid_objects.gltf");
  const test::CommandResult r = test::run_command(test::tessera_exe() + " info '" + path + "'");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.err.find("tessera: warning: " + path + ": ignored, as the scene does not use it: mesh 1 has"),
            std::string::npos)
      << r.err;
}

}  // namespace
}  // namespace tessera
