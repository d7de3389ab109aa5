// Compressed glTF as exporters and optimisers write it: each file loads to what its plain
// original loads to, within the compression's own precision. The files are Khronos' Draco
// samples (scenes/khronos/*/glTF-Draco) and those tests/data/compressed/make.py made with
// gltfpack and cwebp from the plain samples.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <iterator>

#include <draco/attributes/attribute_quantization_transform.h>
#include <draco/compression/decode.h>

#include "scene_io/gltf_loader.h"
#include "scene_io/nodes/gltf_mesh.h"
#include "scene_io/base/load_error.h"
#include "tests/exr_read.h"
#include "tests/test_support.h"

namespace tessera {
namespace {

std::string compressed(const std::string& name) { return test::data_path("compressed/" + name); }

// Every triangle's corners in world space, with their normals (zero when the mesh has none).
struct Corner {
  glm::vec3 p, n;
};
using Triangle = std::array<Corner, 3>;

std::vector<Triangle> world_triangles(const SceneDescription& s) {
  std::vector<Triangle> out;
  for (const Instance& inst : s.instances)
    for (const TriangleMesh& m : s.meshes[inst.mesh].primitives) {
      const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(inst.object_to_world)));
      for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
        Triangle tri;
        for (int k = 0; k < 3; ++k) {
          const std::uint32_t v = m.indices[t + k];
          tri[k].p = glm::vec3(inst.object_to_world * glm::vec4(m.positions[v], 1.0f));
          tri[k].n = m.normals.empty() ? glm::vec3(0) : glm::normalize(normal_matrix * m.normals[v]);
        }
        out.push_back(tri);
      }
    }
  return out;
}

// The largest distance from a triangle of `a` to the nearest triangle of `b` (same winding,
// corners matched under rotation), for positions and for normals. Brute force: the models
// are small.
std::pair<float, float> worst_match(const std::vector<Triangle>& a, const std::vector<Triangle>& b) {
  float worst_p = 0, worst_n = 0;
  for (const Triangle& ta : a) {
    float best_p = INFINITY, best_n = INFINITY;
    for (const Triangle& tb : b)
      for (int r = 0; r < 3; ++r) {
        float dp = 0, dn = 0;
        for (int k = 0; k < 3; ++k) {
          dp = std::max(dp, glm::length(ta[k].p - tb[(k + r) % 3].p));
          dn = std::max(dn, glm::length(ta[k].n - tb[(k + r) % 3].n));
        }
        if (dp < best_p) best_p = dp, best_n = dn;
      }
    worst_p = std::max(worst_p, best_p);
    worst_n = std::max(worst_n, best_n);
  }
  return {worst_p, worst_n};
}

// Draco's quantisation step of the attribute `name` of mesh 0 primitive 0: range / (2^bits - 1),
// as the stream records it.
float draco_step(const std::string& path, const char* name) {
  const GltfDocument doc = read_gltf(path);  // decoded already; the stream is still in its view
  const tinygltf::Primitive& prim = doc.model.meshes[0].primitives[0];
  const tinygltf::Value& ext = prim.extensions.at("KHR_draco_mesh_compression");
  const tinygltf::BufferView& bv = doc.model.bufferViews[ext.Get("bufferView").GetNumberAsInt()];
  draco::DecoderBuffer in;
  in.Init(reinterpret_cast<const char*>(doc.model.buffers[bv.buffer].data.data() + bv.byteOffset), bv.byteLength);
  draco::Decoder decoder;  // keeps the quantised values, and so the transform, when told to skip it
  decoder.SetSkipAttributeTransform(draco::GeometryAttribute::POSITION);
  auto mesh = decoder.DecodeMeshFromBuffer(&in).value();
  const auto* att = mesh->GetAttributeByUniqueId(ext.Get("attributes").Get(name).GetNumberAsInt());
  draco::AttributeQuantizationTransform q;
  EXPECT_TRUE(q.InitFromAttribute(*att)) << name << " is not quantised";
  return q.range() / static_cast<float>((1 << q.quantization_bits()) - 1);
}

// Converted as the renderer gets it: every primitive of every mesh, without placement.
std::vector<Triangle> local_triangles(const std::string& path) {
  const GltfDocument doc = read_gltf(path);
  const AccessorReader reader{doc.model, doc.path};
  SceneDescription s;
  std::vector<std::string> warnings;
  for (const tinygltf::Mesh& m : doc.model.meshes) {
    Mesh mesh;
    for (const tinygltf::Primitive& p : m.primitives) mesh.primitives.push_back(*convert_primitive(reader, p, "", warnings));
    s.meshes.push_back(mesh);
    s.instances.push_back({static_cast<int>(s.meshes.size()) - 1, glm::mat4(1.0f), "", {}});
  }
  return world_triangles(s);
}

TEST(GltfDraco, CesiumManMatchesThePlainFileWithinTheQuantisationStep) {
  const std::string draco = test::scene_path("khronos/CesiumMan/glTF-Draco/CesiumMan.gltf");
  const auto plain = local_triangles(test::scene_path("khronos/CesiumMan/glTF-Binary/CesiumMan.glb"));
  const auto decoded = local_triangles(draco);
  ASSERT_EQ(decoded.size(), plain.size());
  ASSERT_EQ(decoded.size(), 4672u);
  // Each coordinate is off by at most half a step: a corner by sqrt(3)/2 steps.
  const float step = draco_step(draco, "POSITION");
  EXPECT_GT(step, 0.0f);
  EXPECT_LT(step, 1e-3f);
  const auto [dp, dn] = worst_match(decoded, plain);
  EXPECT_LE(dp, 0.87f * step);
  EXPECT_LE(dn, 0.02f);  // octahedral normals
  EXPECT_LE(worst_match(plain, decoded).first, 0.87f * step);
}

TEST(GltfDraco, RiggedSimpleLoadsAsThePlainFile) {
  GltfLoadParams at{};
  at.time = 0.5f;  // skinned and animated: joints and weights decoded as UNSIGNED_SHORT / FLOAT
  const GltfLoadResult plain = load_gltf(test::scene_path("khronos/RiggedSimple/glTF-Binary/RiggedSimple.glb"), at);
  const GltfLoadResult draco = load_gltf(test::scene_path("khronos/RiggedSimple/glTF-Draco/RiggedSimple.gltf"), at);
  const auto a = world_triangles(draco.scene), b = world_triangles(plain.scene);
  ASSERT_EQ(a.size(), 188u);
  ASSERT_EQ(b.size(), 188u);
  const float step = draco_step(test::scene_path("khronos/RiggedSimple/glTF-Draco/RiggedSimple.gltf"), "POSITION");
  EXPECT_LE(worst_match(a, b).first, 2.0f * step);  // quantised weights move skinned corners a little more
  EXPECT_EQ(draco.skins.size(), 1u);
}

// The filters' precision as gltfpack -cc uses them: positions 14 bits (of the box's unit
// extent), normals 8-bit octahedral, rotations 12-bit QUATERNION, translations EXPONENTIAL.
TEST(GltfMeshopt, BoxAnimatedMatchesThePlainFileAtEveryTime) {
  for (float t : {0.0f, 0.6f, 1.2f, 2.0f}) {
    GltfLoadParams at{};
    at.time = t;
    const GltfLoadResult plain = load_gltf(test::scene_path("khronos/BoxAnimated/glTF-Binary/BoxAnimated.glb"), at);
    const GltfLoadResult packed = load_gltf(compressed("boxanimated_meshopt.glb"), at);
    const auto a = world_triangles(packed.scene), b = world_triangles(plain.scene);
    ASSERT_EQ(a.size(), b.size());
    const auto [dp, dn] = worst_match(a, b);
    EXPECT_LE(dp, 4e-3f) << "at t = " << t;  // 14-bit positions under 12-bit rotations
    EXPECT_LE(dn, 0.03f) << "at t = " << t;
    EXPECT_LE(worst_match(b, a).first, 4e-3f) << "at t = " << t;
  }
}

TEST(GltfMeshopt, IndicesModeKeepsTheLinesAndTriangles) {
  const GltfLoadResult plain = load_gltf(test::scene_path("khronos/MeshPrimitiveModes/glTF/MeshPrimitiveModes.gltf"));
  const GltfLoadResult packed = load_gltf(compressed("meshprimitivemodes_meshopt.glb"));
  const auto a = world_triangles(packed.scene), b = world_triangles(plain.scene);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_LE(worst_match(a, b).first, 1e-3f);
}

TEST(GltfMeshopt, QuantizedAccessorsMatchThePlainFile) {
  GltfLoadParams at{};
  at.time = 0.5f;
  const auto a = world_triangles(load_gltf(compressed("riggedsimple_quantized.glb"), at).scene);
  const auto b = world_triangles(load_gltf(test::scene_path("khronos/RiggedSimple/glTF-Binary/RiggedSimple.glb"), at).scene);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_LE(worst_match(a, b).first, 2e-3f);  // 14-bit positions over a 9-unit extent, 8-bit weights
}

TEST(GltfMeshopt, QuantizedMorphTargetsAndWeightKeysMatchThePlainFile) {
  for (float t : {0.0f, 1.0f, 2.5f}) {
    GltfLoadParams at{};
    at.time = t;
    const auto a = world_triangles(load_gltf(compressed("simplemorph_quantized.glb"), at).scene);
    const auto b = world_triangles(load_gltf(test::scene_path("khronos/SimpleMorph/glTF/SimpleMorph.gltf"), at).scene);
    ASSERT_EQ(a.size(), b.size());
    EXPECT_LE(worst_match(a, b).first, 5e-3f) << "at t = " << t;  // 8-bit weight keys, 14-bit positions
  }
}

TEST(GltfWebp, LosslessWebpDecodesToThePngTexels) {
  const GltfLoadResult plain = load_gltf(test::scene_path("khronos/BoxTextured/glTF-Binary/BoxTextured.glb"));
  for (const char* name : {"boxtextured_webp.gltf", "boxtextured_webp_only.gltf"}) {
    const GltfLoadResult webp = load_gltf(compressed(name));
    const int image = webp.scene.materials[0].base_color_texture.image;
    EXPECT_EQ(image, 1) << name << ": the texture shows EXT_texture_webp's source, not the fallback";
    const Image& png = plain.scene.images[0];
    const Image& decoded = webp.scene.images[image];
    EXPECT_EQ(decoded.width, png.width);
    EXPECT_EQ(decoded.height, png.height);
    EXPECT_EQ(decoded.channels, png.channels);
    EXPECT_TRUE(*decoded.pixels == *png.pixels) << name;
  }
}

TEST(GltfWebp, UndecodableWebpFallsBackToTheTexturesSource) {
  std::ifstream in(compressed("boxtextured_webp.gltf"));
  std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  json.replace(json.find("boxtextured.webp"), 16, "boxtextured.bin");  // not an image
  const GltfLoadResult r =
      load_gltf_from_memory({json.begin(), json.end()}, "broken_webp.gltf", test::data_path("compressed"));
  EXPECT_EQ(r.scene.materials[0].base_color_texture.image, 0);  // the PNG fallback
  EXPECT_EQ(r.warnings, std::vector<std::string>{"ignored, as the scene does not use it: image 1 (boxtextured.bin) "
                                                 "could not be decoded: it is not a PNG, JPEG or WebP image"});
}

TEST(GltfBasisu, FallbackSourceIsUsed) {
  const GltfLoadResult r = load_gltf(compressed("boxtextured_basisu_fallback.gltf"));
  EXPECT_EQ(r.scene.materials[0].base_color_texture.image, 0);
  EXPECT_GT(r.scene.images[0].width, 0);
}

TEST(GltfBasisu, WithoutFallbackIsRefusedNamingTheExtension) {
  try {
    load_gltf(compressed("boxtextured_basisu_only.gltf"));
    ADD_FAILURE() << "loaded";
  } catch (const SceneLoadError& e) {
    EXPECT_NE(e.problem().find("KHR_texture_basisu"), std::string::npos) << e.problem();
  }
}

// extensionsRequired comes before every accessor and buffer check: a Draco-like file whose
// indices have no bufferView and whose buffer is missing names the extension.
TEST(GltfExtensionsFirst, UnsupportedRequiredExtensionIsNamedBeforeAccessorProblems) {
  const std::string json = R"({"asset":{"version":"2.0"},"extensionsUsed":["KHR_future_compression"],
    "extensionsRequired":["KHR_future_compression"],"buffers":[{"byteLength":8,"uri":"missing.bin"}],
    "accessors":[{"componentType":5123,"count":3,"type":"SCALAR"}],
    "meshes":[{"primitives":[{"attributes":{},"indices":0}]}]})";
  try {
    load_gltf_from_memory(std::vector<std::uint8_t>(json.begin(), json.end()), "future.gltf", "/nonexistent");
    ADD_FAILURE() << "loaded";
  } catch (const SceneLoadError& e) {
    EXPECT_EQ(e.problem(), "requires extension KHR_future_compression, which tessera does not support");
  }
}

TEST(InfoCli, NamesEveryExtensionWithItsStatus) {
  const auto r = test::run_command(test::tessera_exe() + " info '" + compressed("boxtextured_basisu_fallback.gltf") + "'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("KHR_texture_basisu (used as a fallback: "), std::string::npos) << r.out;
  const auto m = test::run_command(test::tessera_exe() + " info '" + compressed("boxanimated_meshopt.glb") + "'");
  EXPECT_NE(m.out.find("EXT_meshopt_compression (supported)"), std::string::npos) << m.out;
  EXPECT_NE(m.out.find("KHR_mesh_quantization (supported)"), std::string::npos) << m.out;
  EXPECT_EQ(describe_extension_status("KHR_materials_pbrSpecularGlossiness").rfind("ignored: ", 0), 0u);
}

// Rendered, compressed and plain files give the same image within noise (same seed).
double mean_abs_difference(const std::string& a, const std::string& b, const std::string& options) {
  const std::string dir = test::make_temp_dir("compressed_render");
  auto render = [&](const std::string& scene, const std::string& out) {
    const auto r = test::run_command(test::tessera_exe() + " render '" + scene + "' --width 32 --height 32 -q " + options +
                                     " -o '" + dir + "/" + out + "'");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return test::exr_rgb(dir + "/" + out);
  };
  const std::vector<float> x = render(a, "a.exr"), y = render(b, "b.exr");
  EXPECT_EQ(x.size(), y.size());
  double diff = 0, sum = 0;
  for (std::size_t i = 0; i < std::min(x.size(), y.size()); ++i) diff += std::abs(x[i] - y[i]), sum += x[i];
  EXPECT_GT(sum, 0.0);
  return diff / std::max(sum, 1e-9);
}

TEST(CompressedRenderCli, SameImageWithinNoise) {
  const std::string k = test::scene_path("khronos/");
  EXPECT_LT(mean_abs_difference(k + "CesiumMan/glTF-Binary/CesiumMan.glb", k + "CesiumMan/glTF-Draco/CesiumMan.gltf",
                                "--spp 16 --animation none"), 0.03);
  EXPECT_LT(mean_abs_difference(k + "BoxAnimated/glTF-Binary/BoxAnimated.glb", compressed("boxanimated_meshopt.glb"),
                                "--spp 16 --time 0.6"), 0.03);
  EXPECT_EQ(mean_abs_difference(k + "BoxTextured/glTF-Binary/BoxTextured.glb", compressed("boxtextured_webp_only.gltf"),
                                "--spp 4"), 0.0);
}

}  // namespace
}  // namespace tessera
