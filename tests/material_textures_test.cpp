// A material's maps read at a hit (MaterialTable::evaluate) against each map looked up on its
// own (sample_texture, itself tested against the glTF sampler rules in texture_test.cpp):
// where all maps sample alike their texels' places are found once per hit, so a map that
// differs in any one setting (size, texture coordinate set, wrap, filter, transform) must
// still be read at its own places.
#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <random>

#include "renderer/materials/materials.h"

namespace tessera {
namespace {

Image noise_image(int w, int h, unsigned seed) {
  Image img;
  img.width = w, img.height = h, img.channels = 4, img.bits_per_channel = 8;
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(w) * h * 4);
  std::mt19937 rng(seed);
  for (auto& b : bytes) b = static_cast<std::uint8_t>(rng() & 255);
  img.pixels = std::make_shared<const std::vector<std::uint8_t>>(std::move(bytes));
  return img;
}

struct Variant {
  const char* name;
  std::function<void(TextureRef&)> change;  // applied to the metallic-roughness map alone
};

TEST(MaterialTextures, EachMapIsReadAtItsOwnPlacesWhateverTheOthersShare) {
  const Variant variants[] = {
      {"alike", [](TextureRef&) {}},
      {"another size", [](TextureRef& r) { r.image = 2; }},
      {"TEXCOORD_1", [](TextureRef& r) { r.texcoord = 1; }},
      {"clamped", [](TextureRef& r) { r.wrap_s = WrapMode::ClampToEdge; }},
      {"mirrored", [](TextureRef& r) { r.wrap_t = WrapMode::MirroredRepeat; }},
      {"nearest", [](TextureRef& r) { r.filter = FilterMode::Nearest; }},
      {"offset", [](TextureRef& r) { r.transform.offset = vec2(0.3f, -0.1f); }},
      {"rotated", [](TextureRef& r) { r.transform.rotation = 0.5f; }},
      {"scaled", [](TextureRef& r) { r.transform.scale = vec2(2.0f, 1.0f); }},
  };
  for (const Variant& v : variants) {
    SceneDescription scene;
    scene.images = {noise_image(6, 5, 1), noise_image(6, 5, 2), noise_image(7, 3, 3)};
    Material m;
    m.base_color_texture.image = 0;
    m.emissive_texture.image = 1;
    m.emissive_factor = vec3(1.0f);
    m.metallic_roughness_texture.image = 1;
    v.change(m.metallic_roughness_texture);
    scene.materials = {m};
    const MaterialTable table(scene);
    const TextureImage srgb0 = make_texture_image(scene.images[0], ColorEncoding::SRGB);
    const TextureImage srgb1 = make_texture_image(scene.images[1], ColorEncoding::SRGB);
    const Image& mr_image = scene.images[m.metallic_roughness_texture.image];
    const TextureImage linear_mr = make_texture_image(mr_image, ColorEncoding::Linear);
    for (const vec2 uv : {vec2(0.37f, 0.61f), vec2(-0.2f, 1.3f), vec2(0.95f, 0.02f)}) {
      SurfaceHit hit;
      hit.p = vec3(0.0f);
      hit.ng = hit.ns = vec3(0.0f, 0.0f, 1.0f);
      hit.uv[0] = uv;
      hit.uv[1] = vec2(1.0f) - uv;
      hit.material = 0;
      table.prefetch_textures(hit);  // must not change what is read
      const ShadingPoint sp = table.evaluate(hit);
      const vec4 base = sample_texture(srgb0, m.base_color_texture, uv);
      const vec4 mr = sample_texture(linear_mr, m.metallic_roughness_texture, hit.uv[m.metallic_roughness_texture.texcoord]);
      const vec4 glow = sample_texture(srgb1, m.emissive_texture, uv);
      EXPECT_EQ(sp.base_color, glm::clamp(vec3(base), 0.0f, 1.0f)) << v.name;
      EXPECT_EQ(sp.roughness, glm::clamp(mr.g, 0.0f, 1.0f)) << v.name;
      EXPECT_EQ(sp.metallic, glm::clamp(mr.b, 0.0f, 1.0f)) << v.name;
      EXPECT_EQ(sp.emission, vec3(glow)) << v.name;
    }
  }
}

}  // namespace
}  // namespace tessera
