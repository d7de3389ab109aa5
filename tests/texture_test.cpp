// make_texture_image: 8-bit RGBA images are shared with the scene, not copied (a 2048^2
// texture is 16 MiB), and every 8-bit layout reads back as the glTF spec's values.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "renderer/texture.h"

namespace tessera {
namespace {

Image image8(int width, int height, int channels, std::vector<std::uint8_t> bytes) {
  Image img;
  img.width = width;
  img.height = height;
  img.channels = channels;
  img.bits_per_channel = 8;
  img.pixels = std::make_shared<const std::vector<std::uint8_t>>(std::move(bytes));
  return img;
}

// The sRGB transfer function (IEC 61966-2-1), as glTF requires for base colour.
float srgb(float v) { return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f); }

TEST(Texture, RgbaImageIsSharedNotCopied) {
  const Image img = image8(2, 1, 4, {64, 124, 231, 255, 0, 10, 255, 128});
  const TextureImage tex = make_texture_image(img, ColorEncoding::SRGB);
  EXPECT_EQ(tex.texels8.get(), img.pixels.get());
  // The spec's own example: 8-bit [64, 124, 231, 255] decodes to [0.051, 0.202, 0.799, 1.0].
  const vec4 t = tex.texel(0);
  EXPECT_NEAR(t.r, 0.051f, 5e-4f);
  EXPECT_NEAR(t.g, 0.202f, 5e-4f);
  EXPECT_NEAR(t.b, 0.799f, 5e-4f);
  EXPECT_FLOAT_EQ(t.a, 1.0f);
  const vec4 u = make_texture_image(img, ColorEncoding::Linear).texel(1);  // alpha is never sRGB
  EXPECT_FLOAT_EQ(u.g, 10 / 255.0f);
  EXPECT_FLOAT_EQ(u.a, 128 / 255.0f);
}

TEST(Texture, GreyAndRgbExpandToRgba) {
  const TextureImage rgb = make_texture_image(image8(1, 1, 3, {10, 20, 30}), ColorEncoding::SRGB);
  const vec4 c = rgb.texel(0);
  EXPECT_FLOAT_EQ(c.r, srgb(10 / 255.0f));
  EXPECT_FLOAT_EQ(c.b, srgb(30 / 255.0f));
  EXPECT_FLOAT_EQ(c.a, 1.0f);
  const vec4 g = make_texture_image(image8(1, 1, 2, {200, 50}), ColorEncoding::Linear).texel(0);
  EXPECT_FLOAT_EQ(g.r, 200 / 255.0f);
  EXPECT_FLOAT_EQ(g.b, 200 / 255.0f);
  EXPECT_FLOAT_EQ(g.a, 50 / 255.0f);
}

}  // namespace
}  // namespace tessera
