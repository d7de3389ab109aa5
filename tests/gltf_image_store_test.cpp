// Images are decoded when a converted scene shows them, once (scene_io/decode/gltf_image_store.h):
// an image no used material reads is never decoded, so its defects cannot refuse the file,
// and every scene converted from one document shares the same decoded pixels.
#include <gtest/gtest.h>
#include <turbojpeg.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "scene_io/gltf_loader.h"
#include "scene_io/base/load_error.h"
#include "tests/test_support.h"

namespace tessera {
namespace {

std::vector<std::uint8_t> grey_jpeg(int size, std::uint8_t level) {
  const std::vector<std::uint8_t> px(static_cast<std::size_t>(size) * size * 3, level);
  const std::unique_ptr<void, int (*)(tjhandle)> tj(tjInitCompress(), &tjDestroy);
  unsigned char* out = nullptr;
  unsigned long length = 0;
  EXPECT_EQ(tjCompress2(tj.get(), px.data(), size, 0, size, TJPF_RGB, &out, &length, TJSAMP_444, 95, 0), 0);
  std::vector<std::uint8_t> bytes(out, out + length);
  tjFree(out);
  return bytes;
}

// Two scenes of one triangle each: scene 0's material shows image 0, scene 1's image 1.
std::string two_scenes(const std::vector<std::uint8_t>& image0, const std::vector<std::uint8_t>& image1) {
  return R"({"asset": {"version": "2.0"},
    "images": [{"uri": "data:image/jpeg;base64,)" + test::base64(image0) + R"("},
               {"uri": "data:image/jpeg;base64,)" + test::base64(image1) + R"("}],
    "textures": [{"source": 0}, {"source": 1}],
    "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}},
                  {"pbrMetallicRoughness": {"baseColorTexture": {"index": 1}}}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "material": 0}]},
               {"primitives": [{"attributes": {"POSITION": 0}, "material": 1}]}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                   "min": [0, 0, 0], "max": [1, 1, 0]}],
    "bufferViews": [{"buffer": 0, "byteLength": 36}],
    "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
    "nodes": [{"mesh": 0}, {"mesh": 1}], "scenes": [{"nodes": [0]}, {"nodes": [1]}], "scene": 0})";
}

GltfDocument document_of(const std::string& json) {
  return read_gltf_from_memory({json.begin(), json.end()}, "two_scenes.gltf", ".");
}

GltfLoadResult scene(const GltfDocument& document, const std::string& which) {
  GltfLoadParams params;
  params.scene = which;
  return convert_gltf(document, params);
}

TEST(GltfImageStore, OnlyTheImagesTheChosenSceneShowsAreDecoded) {
  const GltfDocument document = document_of(two_scenes(grey_jpeg(8, 200), grey_jpeg(16, 50)));
  const GltfLoadResult first = scene(document, "0");
  ASSERT_EQ(first.scene.images.size(), 2u);
  ASSERT_TRUE(first.scene.images[0].pixels);
  EXPECT_EQ(first.scene.images[0].width, 8);
  EXPECT_EQ((*first.scene.images[0].pixels)[0], 200);  // a flat grey JPEG decodes to its level
  EXPECT_FALSE(first.scene.images[1].pixels);
  EXPECT_FALSE(document.images->decoded(1).pixels) << "scene 1's image was decoded for scene 0";
  const GltfLoadResult second = scene(document, "1");
  ASSERT_TRUE(second.scene.images[1].pixels);
  EXPECT_EQ(second.scene.images[1].width, 16);
  EXPECT_EQ((*second.scene.images[1].pixels)[0], 50);
}

TEST(GltfImageStore, EveryConversionSharesOneDecoding) {
  const GltfDocument document = document_of(two_scenes(grey_jpeg(8, 200), grey_jpeg(16, 50)));
  const GltfLoadResult a = scene(document, "0"), b = scene(document, "0");
  ASSERT_TRUE(a.scene.images[0].pixels);
  EXPECT_EQ(a.scene.images[0].pixels, b.scene.images[0].pixels);  // the same buffer, not a copy
}

TEST(GltfImageStore, ACorruptImageRefusesOnlyTheSceneThatShowsIt) {
  std::vector<std::uint8_t> truncated = grey_jpeg(64, 90);
  truncated.resize(truncated.size() / 2);  // before its scan begins
  const GltfDocument document = document_of(two_scenes(grey_jpeg(8, 200), truncated));
  const GltfLoadResult first = scene(document, "0");
  EXPECT_TRUE(first.warnings.empty()) << first.warnings.front();
  try {
    scene(document, "1");
    FAIL() << "scene 1 loaded with its image truncated";
  } catch (const SceneLoadError& e) {
    EXPECT_EQ(e.problem(),
              "image 1 (data URI) could not be decoded: its JPEG data is corrupt (Invalid JPEG file structure: "
              "missing SOS marker)");
  }
}

// DamagedHelmet's fifth image is its occlusion map, which no slot tessera reads uses (a path
// tracer traces occlusion): 16 MiB and a JPEG decode saved at every load.
TEST(GltfImageStore, DamagedHelmetsOcclusionMapIsNeverDecoded) {
  const GltfDocument document = read_gltf(test::scene_path("khronos/DamagedHelmet/glTF-Binary/DamagedHelmet.glb"));
  const GltfLoadResult r = convert_gltf(document);
  const int occlusion = document.model.textures.at(document.model.materials.at(0).occlusionTexture.index).source;
  ASSERT_GE(occlusion, 0);
  int decoded = 0;
  for (std::size_t i = 0; i < r.scene.images.size(); ++i) {
    if (static_cast<int>(i) == occlusion) continue;
    ASSERT_TRUE(r.scene.images[i].pixels) << "image " << i;
    EXPECT_EQ(r.scene.images[i].width, 2048);
    ++decoded;
  }
  EXPECT_EQ(decoded, 4);
  EXPECT_FALSE(r.scene.images[static_cast<std::size_t>(occlusion)].pixels);
  EXPECT_FALSE(document.images->decoded(occlusion).pixels);
}

}  // namespace
}  // namespace tessera
