// glTF loading (scene_io) on the Khronos sample models in scenes/khronos/ and on small
// hand-made files in tests/data/. No expected value here comes from tessera itself:
//  - unique triangle counts are the README table's (scenes/khronos/README.md);
//  - instanced counts, mesh and instance counts, and world bounds were worked out with a
//    throwaway python3 script (not committed) that walks each file's node tree from its
//    default scene, composes the node matrices / TRS, and transforms the corners of every
//    POSITION accessor's min/max box. Every rotation in these files is a multiple of 90
//    degrees or the geometry is planar, so the corner boxes are the exact bounds (the script
//    also decoded every vertex to confirm). Values are printed to 7 significant digits;
//  - vertex values were decoded from the .bin files with python3's struct module, or are
//    the integers written into tests/data/component_types.bin (listed below);
//  - camera parameters and node transforms are copied from the JSON.
#include <gtest/gtest.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <vector>

#include "scene_io/gltf_loader.h"
#include "scene_io/base/load_error.h"
#include "tests/test_support.h"

namespace tessera {
namespace {

std::uint64_t unique_triangles(const SceneDescription& s) {
  std::uint64_t n = 0;
  for (const Mesh& m : s.meshes)
    for (const TriangleMesh& p : m.primitives) n += p.triangle_count();
  return n;
}

std::uint64_t instanced_triangles(const SceneDescription& s) {
  std::uint64_t n = 0;
  for (const Instance& inst : s.instances)
    for (const TriangleMesh& p : s.meshes.at(inst.mesh).primitives) n += p.triangle_count();
  return n;
}

template <typename Array>
std::vector<float> flat(const Array& v) {
  std::vector<float> out;
  for (const auto& x : v)
    for (int c = 0; c < x.length(); ++c) out.push_back(x[c]);
  return out;
}

void expect_near(glm::vec3 actual, glm::vec3 expected, const std::string& what) {
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(actual[c], expected[c], 1e-6 + 2e-6 * std::abs(expected[c])) << what << " [" << c << "]";
}

const Instance* instance_named(const SceneDescription& s, const std::string& node_name) {
  for (const Instance& inst : s.instances)
    if (inst.node_name == node_name) return &inst;
  return nullptr;
}

const Mesh* mesh_named(const SceneDescription& s, const std::string& name) {
  for (const Mesh& m : s.meshes)
    if (m.name == name) return &m;
  return nullptr;
}

// ---- every sample model: counts, bounds, cameras -------------------------------------

struct Sample {
  const char* file;  // under scenes/khronos/
  std::uint64_t unique, instanced;
  std::size_t meshes, instances, cameras;
  glm::vec3 lo, hi;
};

void PrintTo(const Sample& s, std::ostream* os) { *os << s.file; }

// unique: README column "triangles" (MultipleScenes: see its own test); cameras: README.
const Sample kSamples[] = {
    {"AnisotropyRotationTest/glTF-Binary/AnisotropyRotationTest.glb", 7476, 13876, 6, 11, 0, {-5.556021, -3.53637, -1}, {6.675313, 2.471397, 1}},
    {"AnisotropyStrengthTest/glTF-Binary/AnisotropyStrengthTest.glb", 97240, 97240, 50, 50, 0, {-4.170141, -0.9872717, -0.4}, {3.4, 6.4, 0.4}},
    {"AttenuationTest/glTF-Binary/AttenuationTest.glb", 232, 292, 18, 23, 0, {-10, -10, -2}, {10, 10, 2}},
    {"Box/glTF-Binary/Box.glb", 12, 12, 1, 1, 0, {-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5}},
    // Posed at time 0 by their animations (all play by default).
    {"BoxAnimated/glTF-Binary/BoxAnimated.glb", 254, 254, 2, 2, 0, {-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5}},
    {"BoxTextured/glTF-Binary/BoxTextured.glb", 12, 12, 1, 1, 0, {-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5}},
    {"Cameras/glTF/Cameras.gltf", 2, 2, 1, 1, 2, {0, 0, -0.7075903}, {1, 0.7066229, 0}},
    // Skinned: posed at time 0 by their animations, the bounds those of the skinned vertices.
    {"CesiumMan/glTF-Binary/CesiumMan.glb", 4672, 4672, 1, 1, 0, {-0.3105088, -0.01064529, -0.4465939}, {0.1946552, 1.44716, 0.4498944}},
    {"CesiumMan/glTF-Draco/CesiumMan.gltf", 4672, 4672, 1, 1, 0, {-0.310571, -0.01064654, -0.4465938}, {0.1945348, 1.446842, 0.4500758}},
    {"ClearCoatTest/glTF-Binary/ClearCoatTest.glb", 37116, 37116, 27, 27, 0, {-7.357803, -6.25, -0.06000001}, {3.1, 6.854517, 1.05}},
    {"CornellBox/glTF/cornellBox.gltf", 16720, 16732, 9, 10, 1, {-5.05, -5.05, -5.05}, {5.05, 5.05, 5}},
    {"DamagedHelmet/glTF-Binary/DamagedHelmet.glb", 15452, 15452, 1, 1, 0, {-0.9474586, -0.9009739, -1.187155}, {0.9424954, 0.900995, 0.8128451}},
    {"EmissiveStrengthTest/glTF-Binary/EmissiveStrengthTest.glb", 90, 90, 6, 6, 0, {-8.002613, -6.001067, -2}, {8.001114, 4.009398, 1.998933}},
    {"GlassBrokenWindow/glTF-Binary/GlassBrokenWindow.glb", 987, 987, 3, 3, 0, {-0.2520595, 0.0001517591, -0.01841372}, {0.2559404, 0.5166226, 0.01967429}},
    {"GlassVaseFlowers/glTF-Binary/GlassVaseFlowers.glb", 10218, 14036, 3, 4, 0, {-0.05351734, 0, -0.06829223}, {0.1637571, 0.2032194, 0.07420088}},
    {"InterpolationTest/glTF-Binary/InterpolationTest.glb", 110, 110, 10, 10, 0, {-4.311399, -2.159462, -1}, {4.340119, 7.665226, 1.008945}},
    {"MeshPrimitiveModes/glTF/MeshPrimitiveModes.gltf", 16, 16, 3, 3, 0, {-2.866, -4, 0}, {2.866, -2, 0}},
    {"MetalRoughSpheresNoTextures/glTF-Binary/MetalRoughSpheresNoTextures.glb", 1040409, 1040409, 102, 102, 0, {-0.0009243164, -0.001010498, -0.003349959}, {0.006476563, 0.006494141, 0.0003499593}},
    // README counts both meshes (1 + 2); the default scene (1) places only the square.
    {"MultipleScenes/glTF/MultipleScenes.gltf", 2, 2, 1, 1, 0, {0, 0, 0}, {1, 1, 0}},
    {"MultiUVTest/glTF-Binary/MultiUVTest.glb", 12, 12, 1, 1, 1, {-1, -1, -1}, {1, 1, 1.000001}},
    {"NegativeScaleTest/glTF-Binary/NegativeScaleTest.glb", 3884, 7724, 8, 11, 0, {-5.161674, -4.45354, -0.5}, {5.161674, 4.45354, 0.5}},
    {"OrientationTest/glTF-Binary/OrientationTest.glb", 524, 524, 13, 13, 0, {-5.330651, -5.330651, -5.330651}, {5.330651, 5.330651, 5.330651}},
    {"RiggedSimple/glTF-Binary/RiggedSimple.glb", 188, 188, 1, 1, 0, {-1, -4.575077, -1}, {1, 4.575078, 0.9999996}},
    {"RiggedSimple/glTF-Draco/RiggedSimple.gltf", 188, 188, 1, 1, 0, {-1, -4.575077, -0.9981044}, {0.998104, 4.575078, 0.9999996}},
    {"SimpleMorph/glTF/SimpleMorph.gltf", 1, 1, 1, 1, 0, {0, 0, 0}, {1, 0.5, 0}},  // weights 0, 0 at time 0
    {"SimpleSkin/glTF/SimpleSkin.gltf", 8, 8, 1, 1, 0, {-0.5, 0, 0}, {0.5, 2, 0}},  // bind pose at time 0
    {"SimpleSparseAccessor/glTF/SimpleSparseAccessor.gltf", 12, 12, 1, 1, 0, {0, 0, 0}, {6, 4, 0}},
    {"TextureCoordinateTest/glTF-Binary/TextureCoordinateTest.glb", 10, 10, 5, 5, 0, {-1.2, -1.2, -0.05259115}, {1.2, 1.2, 5.255118e-07}},
    {"TextureSettingsTest/glTF-Binary/TextureSettingsTest.glb", 72, 72, 10, 10, 0, {-5.161674, -5.618556, -0.1500004}, {5.161674, 4.453537, 0.1000003}},
    {"TextureTransformTest/glTF/TextureTransformTest.gltf", 18, 24, 9, 12, 0, {-1.6, -1.141267, 0}, {1.6, 1.05, 0.01}},
    {"TransmissionRoughnessTest/glTF-Binary/TransmissionRoughnessTest.glb", 77792, 77792, 9, 9, 0, {-1, -0.45, -0.15}, {1, 0.45, 0.35}},
    {"TransmissionTest/glTF-Binary/TransmissionTest.glb", 128775, 128775, 22, 22, 1, {-0.9763672, -0.4, -0.5210058}, {0.826243, 0.6205455, 1.368006}},
    {"TriangleWithoutIndices/glTF/TriangleWithoutIndices.gltf", 1, 1, 1, 1, 0, {0, 0, 0}, {1, 1, 0}},
    {"VertexColorTest/glTF-Binary/VertexColorTest.glb", 36, 36, 2, 2, 0, {-1, -1, -0.01274114}, {1, 1, 0.06136632}},
};

class GltfLoaderSamples : public testing::TestWithParam<Sample> {};

TEST_P(GltfLoaderSamples, CountsBoundsAndCameras) {
  const Sample& s = GetParam();
  const SceneDescription scene = load_gltf(test::scene_path(std::string("khronos/") + s.file)).scene;
  EXPECT_EQ(unique_triangles(scene), s.unique);
  EXPECT_EQ(instanced_triangles(scene), s.instanced);
  EXPECT_EQ(scene.meshes.size(), s.meshes);
  EXPECT_EQ(scene.instances.size(), s.instances);
  EXPECT_EQ(scene.cameras.size(), s.cameras);
  expect_near(scene.bounds.lo, s.lo, "bounds.lo");
  expect_near(scene.bounds.hi, s.hi, "bounds.hi");
}

INSTANTIATE_TEST_SUITE_P(Khronos, GltfLoaderSamples, testing::ValuesIn(kSamples),
                         [](const testing::TestParamInfo<Sample>& info) {
                           const std::string f = info.param.file;  // CesiumMan, CesiumMan_Draco
                           const bool draco = f.find("/glTF-Draco/") != std::string::npos;
                           return f.substr(0, f.find('/')) + (draco ? "_Draco" : "");
                         });

// The table above against the README it was taken from: every model listed, with the
// README's triangle and camera counts.
TEST(GltfLoaderSamples, TableMatchesTheReadme) {
  std::ifstream readme(test::scene_path("khronos/README.md"));
  ASSERT_TRUE(readme) << "scenes/khronos/README.md";
  std::size_t rows = 0;
  for (std::string line; std::getline(readme, line);) {
    std::vector<std::string> cells;  // | model | file | triangles | extensions | cameras | ...
    for (std::size_t at = 1; at < line.size();) {
      const std::size_t bar = line.find('|', at);
      if (bar == std::string::npos) break;
      std::string cell = line.substr(at, bar - at);
      cell.erase(0, cell.find_first_not_of(' '));
      cell.erase(cell.find_last_not_of(' ') + 1);
      cells.push_back(cell);
      at = bar + 1;
    }
    if (line.rfind("| ", 0) != 0 || cells.size() < 5 || cells[1].find(".gl") == std::string::npos) continue;
    ++rows;
    const auto it = std::find_if(std::begin(kSamples), std::end(kSamples),
                                 [&](const Sample& s) { return cells[1] == s.file; });
    ASSERT_NE(it, std::end(kSamples)) << cells[1] << " is in the README but not in kSamples";
    const std::uint64_t readme_triangles = std::stoull(cells[2]);
    if (cells[0] == "MultipleScenes") EXPECT_EQ(readme_triangles, 3u);  // both scenes' meshes
    else EXPECT_EQ(readme_triangles, it->unique) << cells[1];
    EXPECT_EQ(std::stoul(cells[4]), it->cameras) << cells[1];
  }
  EXPECT_EQ(rows, std::size(kSamples));
}

// ---- particular features ------------------------------------------------------------

TEST(GltfLoader, SparseAccessorSubstitutesPositions) {
  const SceneDescription s =
      load_gltf(test::scene_path("khronos/SimpleSparseAccessor/glTF/SimpleSparseAccessor.gltf")).scene;
  ASSERT_EQ(s.meshes.size(), 1u);
  ASSERT_EQ(s.meshes[0].primitives.size(), 1u);
  const TriangleMesh& m = s.meshes[0].primitives[0];
  // Dense: a 7 x 2 grid, (i, 0, 0) then (i, 1, 0); sparse indices 8, 10, 12 (UNSIGNED_SHORT)
  // replace (1,1,0), (3,1,0), (5,1,0) with (1,2,0), (3,3,0), (5,4,0).
  const std::vector<float> expected = {0, 0, 0, 1, 0, 0, 2, 0, 0, 3, 0, 0, 4, 0, 0, 5, 0, 0, 6, 0, 0,
                                       0, 1, 0, 1, 2, 0, 2, 1, 0, 3, 3, 0, 4, 1, 0, 5, 4, 0, 6, 1, 0};
  EXPECT_EQ(flat(m.positions), expected);
  const MeshArray<std::uint32_t> indices = {0, 8, 7, 0, 1, 8, 1, 9, 8, 1, 2, 9, 2, 10, 9, 2, 3, 10,
                                              3, 11, 10, 3, 4, 11, 4, 12, 11, 4, 5, 12, 5, 13, 12, 5, 6, 13};
  EXPECT_EQ(m.indices, indices);
}

TEST(GltfLoader, StripsAndFansBecomeTrianglesPointsAndLinesAreSkippedWithOneWarning) {
  const GltfLoadResult r =
      load_gltf(test::scene_path("khronos/MeshPrimitiveModes/glTF/MeshPrimitiveModes.gltf"));
  EXPECT_EQ(r.warnings, std::vector<std::string>{"points and lines are not rendered; such primitives were skipped"});
  // Four meshes hold only points or lines; they are neither stored nor placed.
  ASSERT_EQ(r.scene.meshes.size(), 3u);
  const Mesh* tris = mesh_named(r.scene, "mesh with TRIANGLES");
  const Mesh* strip = mesh_named(r.scene, "mesh with GL_TRIANGLE_STRIP");
  const Mesh* fan = mesh_named(r.scene, "mesh with GL_TRIANGLE_FAN");
  ASSERT_TRUE(tris && strip && fan);
  EXPECT_EQ(tris->primitives.at(0).triangle_count(), 6u);  // 18 indices
  // Strip indices 2 3 1 4 6 5: triangle i = {v_i, v_(i+1+i%2), v_(i+2-i%2)} (glTF spec).
  EXPECT_EQ(strip->primitives.at(0).indices,
            (MeshArray<std::uint32_t>{2, 3, 1, 3, 4, 1, 1, 4, 6, 4, 5, 6}));
  // Fan indices 0 1 2 3 4 5 6 1: triangle i = {v_(i+1), v_(i+2), v_0}.
  EXPECT_EQ(fan->primitives.at(0).indices,
            (MeshArray<std::uint32_t>{1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 5, 0, 5, 6, 0, 6, 1, 0}));
}

TEST(GltfLoader, MultipleScenesDefaultAndChosenByIndex) {
  const std::string path = test::scene_path("khronos/MultipleScenes/glTF/MultipleScenes.gltf");
  const SceneDescription by_default = load_gltf(path).scene;  // "scene": 1, the square
  EXPECT_EQ(by_default.scene_name, "1");
  EXPECT_EQ(unique_triangles(by_default), 2u);
  const SceneDescription first = load_gltf(path, GltfLoadParams{"0"}).scene;  // the triangle
  EXPECT_EQ(first.scene_name, "0");
  EXPECT_EQ(unique_triangles(first), 1u);
  EXPECT_EQ(unique_triangles(first) + unique_triangles(by_default), 3u);  // the README's count
  const SceneDescription second = load_gltf(path, GltfLoadParams{"1"}).scene;
  EXPECT_EQ(unique_triangles(second), 2u);
  try {
    load_gltf(path, GltfLoadParams{"2"});
    FAIL() << "scene 2 does not exist";
  } catch (const SceneLoadError& e) {
    EXPECT_EQ(e.problem(), "has no scene '2' (it has 2 scenes: 0, 1)");
  }
}

TEST(GltfLoader, ScenesChosenByNameBeforeIndex) {
  // tests/data/named_scenes.gltf: scene 0 'quad' (2 triangles, the default), scene 1
  // 'triangle' (1 triangle, placed at z = 5), scene 2 named '0' (both).
  const std::string path = test::data_path("named_scenes.gltf");
  EXPECT_EQ(load_gltf(path).scene.scene_name, "quad");
  const SceneDescription triangle = load_gltf(path, GltfLoadParams{"triangle"}).scene;
  EXPECT_EQ(unique_triangles(triangle), 1u);
  ASSERT_EQ(triangle.instances.size(), 1u);
  EXPECT_EQ(triangle.instances[0].object_to_world[3], glm::vec4(0, 0, 5, 1));
  const SceneDescription named_zero = load_gltf(path, GltfLoadParams{"0"}).scene;
  EXPECT_EQ(named_zero.scene_name, "0");
  EXPECT_EQ(unique_triangles(named_zero), 3u);
  EXPECT_EQ(unique_triangles(load_gltf(path, GltfLoadParams{"1"}).scene), 1u);
  try {
    load_gltf(path, GltfLoadParams{"nosuch"});
    FAIL() << "there is no scene 'nosuch'";
  } catch (const SceneLoadError& e) {
    EXPECT_EQ(e.problem(), "has no scene 'nosuch' (it has 3 scenes: 0 'quad', 1 'triangle', 2 '0')");
  }
}

TEST(GltfLoader, NegativeScaleInstancesHaveNegativeDeterminant) {
  const SceneDescription s =
      load_gltf(test::scene_path("khronos/NegativeScaleTest/glTF-Binary/NegativeScaleTest.glb")).scene;
  // By hand from the node scales: NegativeScaleFront (-1,-1,-1), NotShinyMinus1 (-1,-1,-1),
  // Shiny1 and Dark1 (parents scaled -1,-1,-1); ShinyMinus1 and DarkMinus1 flip twice.
  std::set<std::string> negative;
  for (const Instance& inst : s.instances)
    if (glm::determinant(glm::mat3(inst.object_to_world)) < 0) negative.insert(inst.node_name);
  EXPECT_EQ(negative, (std::set<std::string>{"NegativeScaleFront", "NotShinyMinus1", "Shiny1", "Dark1"}));
}

TEST(GltfLoader, PerspectiveAndOrthographicCameras) {
  const SceneDescription s = load_gltf(test::scene_path("khronos/Cameras/glTF/Cameras.gltf")).scene;
  ASSERT_EQ(s.cameras.size(), 2u);
  const glm::mat4 at_05_05_3(glm::vec4(1, 0, 0, 0), glm::vec4(0, 1, 0, 0), glm::vec4(0, 0, 1, 0),
                             glm::vec4(0.5f, 0.5f, 3.0f, 1));  // nodes 1 and 2: translation only
  const Camera& p = s.cameras[0];
  EXPECT_EQ(p.projection, Camera::Projection::Perspective);
  EXPECT_FLOAT_EQ(p.yfov, 0.7f);
  EXPECT_FLOAT_EQ(p.aspect_ratio, 1.0f);
  EXPECT_FLOAT_EQ(p.znear, 0.01f);
  EXPECT_FLOAT_EQ(p.zfar, 100.0f);
  EXPECT_EQ(p.camera_to_world, at_05_05_3);
  const Camera& o = s.cameras[1];
  EXPECT_EQ(o.projection, Camera::Projection::Orthographic);
  EXPECT_FLOAT_EQ(o.xmag, 1.0f);
  EXPECT_FLOAT_EQ(o.ymag, 1.0f);
  EXPECT_EQ(o.camera_to_world, at_05_05_3);
}

TEST(GltfLoader, CornellBoxCameraAndOneMeshPlacedTwice) {
  const SceneDescription s = load_gltf(test::scene_path("khronos/CornellBox/glTF/cornellBox.gltf")).scene;
  ASSERT_EQ(s.cameras.size(), 1u);
  EXPECT_EQ(s.cameras[0].name, "default");
  EXPECT_FLOAT_EQ(s.cameras[0].yfov, 0.7175414562225342f);
  EXPECT_FLOAT_EQ(s.cameras[0].aspect_ratio, 1.3333333333333333f);
  EXPECT_NEAR(s.cameras[0].camera_to_world[3].z, 19.992091970966317, 1e-5);
  // Nodes cube_instance_2 and cube_instance_3 both place mesh 1 (at y = -5 and y = +5);
  // the other eight nodes place a mesh each: 9 meshes stored, 10 instances.
  const Instance* below = instance_named(s, "cube_instance_2");
  const Instance* above = instance_named(s, "cube_instance_3");
  ASSERT_TRUE(below && above);
  EXPECT_EQ(below->mesh, above->mesh);
  EXPECT_EQ(below->object_to_world[3], glm::vec4(0, -5, 0, 1));
  EXPECT_EQ(above->object_to_world[3], glm::vec4(0, 5, 0, 1));
  std::set<int> meshes;
  for (const Instance& inst : s.instances) meshes.insert(inst.mesh);
  EXPECT_EQ(meshes.size(), 9u);
  EXPECT_EQ(s.meshes.size(), 9u);
}

TEST(GltfLoader, SharedMeshIsStoredOnceAndPlacedThrice) {
  // tests/data/shared_mesh.gltf: the unit quad (0..1, 0..1, 0) placed by node 'moved'
  // (translation 10,0,0), node 'child' (translation 0,5,0 under 'parent', scale 2) and
  // node 'mirrored' (scale -1,1,1, translation 0,0,-4).
  const SceneDescription s = load_gltf(test::data_path("shared_mesh.gltf")).scene;
  ASSERT_EQ(s.meshes.size(), 1u);
  ASSERT_EQ(s.instances.size(), 3u);
  EXPECT_EQ(unique_triangles(s), 2u);
  EXPECT_EQ(instanced_triangles(s), 6u);
  EXPECT_EQ(s.instances[0].node_name, "moved");
  EXPECT_EQ(s.instances[1].node_name, "child");
  EXPECT_EQ(s.instances[2].node_name, "mirrored");
  for (const Instance& inst : s.instances) EXPECT_EQ(inst.mesh, 0);
  EXPECT_EQ(s.instances[0].object_to_world[3], glm::vec4(10, 0, 0, 1));
  EXPECT_EQ(s.instances[1].object_to_world,
            glm::mat4(glm::vec4(2, 0, 0, 0), glm::vec4(0, 2, 0, 0), glm::vec4(0, 0, 2, 0), glm::vec4(0, 10, 0, 1)));
  EXPECT_LT(glm::determinant(glm::mat3(s.instances[2].object_to_world)), 0.0f);
  // x: -1 (mirrored) .. 11 (moved); y: 0 .. 12 (child: 2 * (1 + 5)); z: -4 .. 0.
  EXPECT_EQ(s.bounds.lo, glm::vec3(-1, 0, -4));
  EXPECT_EQ(s.bounds.hi, glm::vec3(11, 12, 0));
}

TEST(GltfLoader, TriangleWithoutIndicesUsesVertexOrder) {
  const SceneDescription s =
      load_gltf(test::scene_path("khronos/TriangleWithoutIndices/glTF/TriangleWithoutIndices.gltf")).scene;
  ASSERT_EQ(s.meshes.size(), 1u);
  const TriangleMesh& m = s.meshes[0].primitives.at(0);
  EXPECT_EQ(flat(m.positions), (std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0}));
  EXPECT_EQ(m.indices, (MeshArray<std::uint32_t>{0, 1, 2}));
}

TEST(GltfLoader, DataUriBuffer) {
  // tests/data/data_uri_triangle.gltf: indices and positions base64 in a data URI.
  const SceneDescription s = load_gltf(test::data_path("data_uri_triangle.gltf")).scene;
  ASSERT_EQ(s.meshes.size(), 1u);
  const TriangleMesh& m = s.meshes[0].primitives.at(0);
  EXPECT_EQ(flat(m.positions), (std::vector<float>{-1, 0.5, 2, 3, 0.5, 2, -1, 4.5, 2}));
  EXPECT_EQ(m.indices, (MeshArray<std::uint32_t>{0, 1, 2}));
  EXPECT_EQ(s.bounds.lo, glm::vec3(-1, 0.5, 2));
  EXPECT_EQ(s.bounds.hi, glm::vec3(3, 4.5, 2));
}

// ---- every accessor component type -----------------------------------------------------

// tests/data/component_types.gltf (+ .bin, KHR_mesh_quantization): one mesh, four
// primitives. The raw integers written to the .bin are in the comments; normalized values
// follow the glTF spec: unsigned c / (2^n - 1), signed max(c / (2^(n-1) - 1), -1).
class GltfLoaderComponentTypes : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    scene_ = new SceneDescription(load_gltf(test::data_path("component_types.gltf")).scene);
  }
  static void TearDownTestSuite() { delete scene_; }
  const TriangleMesh& prim(int i) { return scene_->meshes.at(0).primitives.at(i); }
  static SceneDescription* scene_;
};
SceneDescription* GltfLoaderComponentTypes::scene_ = nullptr;

float u8(int c) { return static_cast<float>(c / 255.0); }
float u16(int c) { return static_cast<float>(c / 65535.0); }
float s8(int c) { return static_cast<float>(std::max(c / 127.0, -1.0)); }
float s16(int c) { return static_cast<float>(std::max(c / 32767.0, -1.0)); }

TEST_F(GltfLoaderComponentTypes, InterleavedFloatsWithByteStride) {
  // POSITION and NORMAL interleaved in one view, byteStride 32 (24 bytes + 8 of 0xFF).
  EXPECT_EQ(flat(prim(0).positions), (std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0}));
  EXPECT_EQ(flat(prim(0).normals), (std::vector<float>{0, 0, 1, 0, 1, 0, 1, 0, 0}));
}

TEST_F(GltfLoaderComponentTypes, NormalizedUnsignedByteAndShort) {
  // TEXCOORD_0 UNSIGNED_BYTE normalized (stride 4): (0,255) (51,128) (255,1).
  EXPECT_EQ(flat(prim(0).texcoords0), (std::vector<float>{0, 1, u8(51), u8(128), 1, u8(1)}));
  // COLOR_0 UNSIGNED_SHORT normalized VEC4: (65535,0,32768,65535) (0,65535,13107,65535) (1,2,3,4).
  EXPECT_EQ(flat(prim(0).colors), (std::vector<float>{1, 0, u16(32768), 1, 0, 1, u16(13107), 1,
                                                      u16(1), u16(2), u16(3), u16(4)}));
  // TEXCOORD_0 UNSIGNED_SHORT normalized: (0,65535) (65535,0) (32767,13107).
  EXPECT_EQ(flat(prim(1).texcoords0), (std::vector<float>{0, 1, 1, 0, u16(32767), u16(13107)}));
  // COLOR_0 UNSIGNED_BYTE normalized VEC3 (stride 4): (255,0,0) (0,255,51) (1,2,3); alpha 1.
  EXPECT_EQ(flat(prim(1).colors),
            (std::vector<float>{1, 0, 0, 1, 0, 1, u8(51), 1, u8(1), u8(2), u8(3), 1}));
}

TEST_F(GltfLoaderComponentTypes, QuantizedSignedAndUnnormalizedIntegers) {
  // POSITION SHORT (stride 8): (-3,7,100) (32767,-32768,0) (1,2,3).
  EXPECT_EQ(flat(prim(2).positions), (std::vector<float>{-3, 7, 100, 32767, -32768, 0, 1, 2, 3}));
  // NORMAL BYTE normalized (stride 4): (127,0,0) (0,-128,64) (-64,0,127); -128 clamps to -1.
  EXPECT_EQ(flat(prim(2).normals), (std::vector<float>{1, 0, 0, 0, -1, s8(64), s8(-64), 0, 1}));
  // TEXCOORD_0 BYTE normalized: (-128,127) (0,-64) (1,2).
  EXPECT_EQ(flat(prim(2).texcoords0), (std::vector<float>{-1, 1, 0, s8(-64), s8(1), s8(2)}));
  // TEXCOORD_1 UNSIGNED_BYTE, not normalized: (0,1) (2,3) (255,7).
  EXPECT_EQ(flat(prim(2).texcoords1), (std::vector<float>{0, 1, 2, 3, 255, 7}));
  // POSITION UNSIGNED_BYTE normalized: (0,0,0) (255,0,0) (0,51,255).
  EXPECT_EQ(flat(prim(3).positions), (std::vector<float>{0, 0, 0, 1, 0, 0, 0, u8(51), 1}));
  // TEXCOORD_0 SHORT, not normalized: (-5,6) (7,-8) (0,300).
  EXPECT_EQ(flat(prim(3).texcoords0), (std::vector<float>{-5, 6, 7, -8, 0, 300}));
  // TEXCOORD_1 SHORT normalized: (-32768,32767) (16384,0) (-1,1).
  EXPECT_EQ(flat(prim(3).texcoords1), (std::vector<float>{-1, 1, s16(16384), 0, s16(-1), s16(1)}));
}

TEST_F(GltfLoaderComponentTypes, IndicesOfEveryUnsignedType) {
  EXPECT_EQ(prim(0).indices, (MeshArray<std::uint32_t>{0, 1, 2}));  // UNSIGNED_BYTE
  EXPECT_EQ(prim(1).indices, (MeshArray<std::uint32_t>{2, 1, 0}));  // UNSIGNED_SHORT
  EXPECT_EQ(prim(2).indices, (MeshArray<std::uint32_t>{0, 2, 1}));  // UNSIGNED_INT
  EXPECT_EQ(prim(3).indices, (MeshArray<std::uint32_t>{0, 1, 2}));  // none: vertex order
  // Bounds span every primitive: x -3 .. 32767, y -32768 .. 7, z 0 .. 100.
  EXPECT_EQ(scene_->bounds.lo, glm::vec3(-3, -32768, 0));
  EXPECT_EQ(scene_->bounds.hi, glm::vec3(32767, 7, 100));
}

// ---- files built in memory --------------------------------------------------------------

// A one-triangle glTF (no indices) whose three positions are `xyz`.
std::vector<std::uint8_t> triangle_gltf(const std::vector<float>& xyz) {
  std::vector<std::uint8_t> bin(xyz.size() * 4);
  std::memcpy(bin.data(), xyz.data(), bin.size());
  const std::string json = R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
                           R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
                           R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3",)"
                           R"("min":[0,0,0],"max":[1,1,0]}],)"  // the finite triangle's bounds (glTF requires them)
                           R"("bufferViews":[{"buffer":0,"byteLength":36}],)"
                           R"("buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,)" +
                           test::base64(bin) + "\"}]}";
  return {json.begin(), json.end()};
}

// `text` with its first `from` made `to` (a test's edit of triangle_gltf's JSON).
void replace_first(std::string& text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  ASSERT_NE(at, std::string::npos) << from;
  text.replace(at, from.size(), to);
}

TEST(GltfLoader, NonFinitePositionsAreRejected) {
  const float nan = std::nanf(""), inf = INFINITY;
  const SceneDescription ok = load_gltf_from_memory(triangle_gltf({0, 0, 0, 1, 0, 0, 0, 1, 0}), "ok.gltf", ".").scene;
  EXPECT_EQ(ok.bounds.hi, glm::vec3(1, 1, 0));
  struct Case { std::vector<float> xyz; const char* problem; };
  const Case cases[] = {
      {{nan, 0, 0, 1, 0, 0, 0, 1, 0}, "accessor 0 (POSITION of mesh 0 primitive 0) holds NaN at element 0"},
      {{0, 0, 0, 1, 0, nan, 0, 1, 0}, "accessor 0 (POSITION of mesh 0 primitive 0) holds NaN at element 1"},
      {{0, 0, 0, 1, 0, 0, 0, inf, 0}, "accessor 0 (POSITION of mesh 0 primitive 0) holds +infinity at element 2"},
      {{0, 0, 0, 1, 0, 0, 0, 1, -inf}, "accessor 0 (POSITION of mesh 0 primitive 0) holds -infinity at element 2"},
  };
  for (const Case& c : cases) {
    try {
      load_gltf_from_memory(triangle_gltf(c.xyz), "bad.gltf", ".");
      ADD_FAILURE() << "loaded: " << c.problem;
    } catch (const SceneLoadError& e) {
      EXPECT_EQ(e.file(), "bad.gltf");
      EXPECT_EQ(e.problem(), c.problem);
    }
  }
}

// A camera 10 in front of a unit triangle: a znear beyond its farthest corner (10.1) or a
// zfar short of its nearest point (10) leaves only the background, and says so.
TEST(GltfLoader, ACameraWhoseClippingPlanesLeaveOutTheWholeSceneIsWarnedAbout) {
  auto warnings_for = [](const std::string& planes) {
    const std::vector<std::uint8_t> tri = triangle_gltf({0, 0, 0, 1, 0, 0, 0, 1, 0});
    std::string json(tri.begin(), tri.end());
    replace_first(json, R"("scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)",
                  R"("scenes":[{"nodes":[0,1]}],"nodes":[{"mesh":0},{"camera":0,"translation":[0,0,10]}],)"
                  R"("cameras":[{"name":"eye","type":"perspective","perspective":{"yfov":0.5,)" + planes + "}}],");
    return load_gltf_from_memory({json.begin(), json.end()}, "clip.gltf", ".").warnings;
  };
  EXPECT_EQ(warnings_for(R"("znear":0.01,"zfar":100)"), std::vector<std::string>{});
  EXPECT_EQ(warnings_for(R"("znear":10.05)"), std::vector<std::string>{});  // the far corners remain
  EXPECT_EQ(warnings_for(R"("znear":20)"),
            std::vector<std::string>{"camera 'eye' shows only the background: its znear 20 lies beyond the whole scene "
                                     "(at most 10.1 from it)"});
  EXPECT_EQ(warnings_for(R"("znear":0.01,"zfar":5)"),
            std::vector<std::string>{"camera 'eye' shows only the background: its zfar 5 falls short of the whole "
                                     "scene (at least 10 from it)"});
}

TEST(GltfLoader, DeepHierarchyIsWalkedWithoutRecursion) {
  // 200000 nodes in a chain, each translated by 0.5 in y; the last places the mesh. A
  // recursive walk would overflow the stack; the leaf lands exactly at y = 100000.
  const int n = 200000;
  std::string nodes;
  for (int i = 0; i + 1 < n; ++i) nodes += R"({"translation":[0,0.5,0],"children":[)" + std::to_string(i + 1) + "]},";
  nodes += R"({"translation":[0,0.5,0],"mesh":0})";
  const std::vector<std::uint8_t> tri = triangle_gltf({0, 0, 0, 1, 0, 0, 0, 1, 0});
  std::string json(tri.begin(), tri.end());
  replace_first(json, R"([{"mesh":0}])", "[" + nodes + "]");
  const SceneDescription s = load_gltf_from_memory({json.begin(), json.end()}, "deep.gltf", ".").scene;
  ASSERT_EQ(s.instances.size(), 1u);
  EXPECT_EQ(s.instances[0].object_to_world[3], glm::vec4(0, 0.5f * n, 0, 1));
}

}  // namespace
}  // namespace tessera
