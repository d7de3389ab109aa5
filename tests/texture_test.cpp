// Texture lookups against a second method: bilinear and nearest filtering written directly
// from the glTF sampler rules on the source image's row-major pixels (the texel centres at
// (i + 0.5) / width; REPEAT, CLAMP_TO_EDGE and MIRRORED_REPEAT as OpenGL defines them). The
// renderer stores texels in 4x4 blocks and skips wrapping inside the image: sizes that are
// not multiples of 4, coordinates far outside [0, 1] and every wrap mode must not notice.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <random>

#include "renderer/materials/texture.h"

namespace tessera {
namespace {

Image ramp_image(int w, int h, int bits) {
  Image img;
  img.width = w, img.height = h, img.channels = 4, img.bits_per_channel = bits;
  const std::size_t n = static_cast<std::size_t>(w) * h * 4;
  std::vector<std::uint8_t> bytes(n * (bits / 8));
  std::mt19937 rng(static_cast<unsigned>(w * 31 + h));
  for (std::size_t k = 0; k < n; ++k) {
    if (bits == 8) {
      bytes[k] = static_cast<std::uint8_t>(rng() & 255);
    } else {
      const float v = static_cast<float>(rng() % 1000) / 999.0f;
      std::memcpy(&bytes[4 * k], &v, 4);
    }
  }
  img.pixels = std::make_shared<const std::vector<std::uint8_t>>(std::move(bytes));
  return img;
}

int wrap_reference(int i, int n, WrapMode mode) {
  if (mode == WrapMode::ClampToEdge) return std::clamp(i, 0, n - 1);
  const int m = ((i % (2 * n)) + 2 * n) % (2 * n);
  if (mode == WrapMode::MirroredRepeat) return m < n ? m : 2 * n - 1 - m;
  return m % n;
}

vec4 texel_reference(const Image& img, int i, int j, ColorEncoding enc) {
  const std::size_t at = (static_cast<std::size_t>(j) * img.width + i) * 4;
  vec4 c;
  for (int k = 0; k < 4; ++k) {
    float v;
    const std::uint8_t* px = img.pixels->data();
    if (img.bits_per_channel == 8) v = px[at + k] / 255.0f;
    else std::memcpy(&v, &px[4 * (at + k)], 4);
    c[k] = enc == ColorEncoding::SRGB && k < 3 ? srgb_to_linear(v) : v;
  }
  return c;
}

vec4 lookup_reference(const Image& img, const TextureRef& ref, vec2 uv, ColorEncoding enc) {
  const float x = uv.x * img.width - 0.5f, y = uv.y * img.height - 0.5f;  // the texel-centre convention
  const int i = static_cast<int>(std::floor(x)), j = static_cast<int>(std::floor(y));
  const float dx = x - std::floor(x), dy = y - std::floor(y);
  auto t = [&](int a, int b) {
    return texel_reference(img, wrap_reference(a, img.width, ref.wrap_s), wrap_reference(b, img.height, ref.wrap_t), enc);
  };
  if (ref.filter == FilterMode::Nearest) return t(i + (dx >= 0.5f), j + (dy >= 0.5f));
  const float fx = dx, fy = dy;
  return (1 - fx) * (1 - fy) * t(i, j) + fx * (1 - fy) * t(i + 1, j) + (1 - fx) * fy * t(i, j + 1) + fx * fy * t(i + 1, j + 1);
}

TEST(Texture, LookupsEqualTheSamplerRulesOnRowMajorPixels) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> uv(-3.0f, 4.0f);
  for (int bits : {8, 32}) {
    for (auto [w, h] : {std::pair{1, 1}, {5, 3}, {4, 4}, {17, 9}, {64, 33}}) {
      const Image img = ramp_image(w, h, bits);
      for (ColorEncoding enc : {ColorEncoding::Linear, ColorEncoding::SRGB}) {
        const TextureImage tex = make_texture_image(img, enc);
        for (WrapMode s : {WrapMode::Repeat, WrapMode::ClampToEdge, WrapMode::MirroredRepeat})
          for (WrapMode t : {WrapMode::Repeat, WrapMode::ClampToEdge, WrapMode::MirroredRepeat})
            for (FilterMode f : {FilterMode::Linear, FilterMode::Nearest}) {
              TextureRef ref;
              ref.image = 0, ref.wrap_s = s, ref.wrap_t = t, ref.filter = f;
              for (int k = 0; k < 300; ++k) {
                const vec2 at(uv(rng), uv(rng));
                const vec4 got = sample_texture(tex, ref, at), want = lookup_reference(img, ref, at, enc);
                for (int c = 0; c < 4; ++c)
                  ASSERT_NEAR(got[c], want[c], 2e-6f) << w << "x" << h << " bits " << bits << " uv " << at.x << "," << at.y;
              }
            }
      }
    }
  }
}

// Lookups one after another at the same point, of textures that differ in one thing each
// (size, a wrap mode, the filter, the transform): each follows its own rules, and
// same_sampling, by which a material's maps share their texels' places, tells them apart.
TEST(Texture, LookupsThatDifferInOneSettingEachFollowTheirOwn) {
  const Image wide = ramp_image(5, 3, 8), tall = ramp_image(3, 5, 8);
  const TextureImage wide_tex = make_texture_image(wide, ColorEncoding::Linear);
  const TextureImage tall_tex = make_texture_image(tall, ColorEncoding::Linear);
  TextureRef plain;
  plain.image = 0;
  TextureRef clamp_s = plain, mirror_t = plain, nearest = plain, shifted = plain;
  clamp_s.wrap_s = WrapMode::ClampToEdge;
  mirror_t.wrap_t = WrapMode::MirroredRepeat;
  nearest.filter = FilterMode::Nearest;
  shifted.transform.offset = vec2(0.3f, 0.0f);  // rotation 0, scale 1: uv + offset exactly
  TextureRef other_image = plain, second_set = plain;
  other_image.image = 1;  // another image of the same size samples alike
  second_set.texcoord = 1;
  EXPECT_TRUE(same_sampling(wide_tex, plain, wide_tex, plain));
  EXPECT_TRUE(same_sampling(wide_tex, plain, wide_tex, other_image));
  EXPECT_FALSE(same_sampling(wide_tex, plain, tall_tex, plain));
  for (const TextureRef* r : {&clamp_s, &mirror_t, &nearest, &shifted, &second_set}) {
    EXPECT_FALSE(same_sampling(wide_tex, plain, wide_tex, *r));
    EXPECT_FALSE(same_sampling(wide_tex, *r, wide_tex, plain));
  }
  for (const vec2 uv : {vec2(-0.37f, 1.71f), vec2(0.52f, 0.48f), vec2(2.9f, -1.2f)}) {
    for (int round = 0; round < 2; ++round) {
      const struct {
        const TextureImage& tex;
        const Image& img;
        const TextureRef& ref;
        vec2 at;
      } lookups[] = {{wide_tex, wide, plain, uv},     {wide_tex, wide, clamp_s, uv},  {wide_tex, wide, mirror_t, uv},
                     {wide_tex, wide, nearest, uv},   {tall_tex, tall, plain, uv},    {wide_tex, wide, shifted, uv},
                     {wide_tex, wide, plain, uv + vec2(0.3f, 0.0f)}};
      for (const auto& l : lookups) {
        const vec2 reference_at = &l.ref == &shifted ? l.at + shifted.transform.offset : l.at;
        const vec4 got = sample_texture(l.tex, l.ref, l.at), want = lookup_reference(l.img, l.ref, reference_at, ColorEncoding::Linear);
        for (int c = 0; c < 4; ++c) ASSERT_NEAR(got[c], want[c], 2e-6f) << "uv " << uv.x << "," << uv.y << " lookup " << (&l - lookups);
      }
    }
  }
}

// Each texel centre returns exactly that texel: nothing is blended across the 4x4 blocks'
// borders or lost at the padding of a size that is not a multiple of 4.
TEST(Texture, TexelCentresReturnTheirTexelAcrossBlockBorders) {
  const Image img = ramp_image(7, 6, 8);
  const TextureImage tex = make_texture_image(img, ColorEncoding::Linear);
  TextureRef ref;
  ref.image = 0;
  for (int j = 0; j < img.height; ++j)
    for (int i = 0; i < img.width; ++i) {
      const vec4 got = sample_texture(tex, ref, vec2((i + 0.5f) / img.width, (j + 0.5f) / img.height));
      const vec4 want = texel_reference(img, i, j, ColorEncoding::Linear);
      for (int c = 0; c < 4; ++c) EXPECT_FLOAT_EQ(got[c], want[c]) << "texel " << i << "," << j;
    }
}

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

TEST(Texture, ReadsTheSpecsSrgbExample) {
  const Image img = image8(2, 1, 4, {64, 124, 231, 255, 0, 10, 255, 128});
  const TextureImage tex = make_texture_image(img, ColorEncoding::SRGB);
  // The spec's own example: 8-bit [64, 124, 231, 255] decodes to [0.051, 0.202, 0.799, 1.0].
  const vec4 t = tex.texel(0, 0);
  EXPECT_NEAR(t.r, 0.051f, 5e-4f);
  EXPECT_NEAR(t.g, 0.202f, 5e-4f);
  EXPECT_NEAR(t.b, 0.799f, 5e-4f);
  EXPECT_FLOAT_EQ(t.a, 1.0f);
  const vec4 u = make_texture_image(img, ColorEncoding::Linear).texel(1, 0);  // alpha is never sRGB
  EXPECT_FLOAT_EQ(u.g, 10 / 255.0f);
  EXPECT_FLOAT_EQ(u.a, 128 / 255.0f);
}

TEST(Texture, GreyAndRgbExpandToRgba) {
  const TextureImage rgb = make_texture_image(image8(1, 1, 3, {10, 20, 30}), ColorEncoding::SRGB);
  const vec4 c = rgb.texel(0, 0);
  EXPECT_FLOAT_EQ(c.r, srgb(10 / 255.0f));
  EXPECT_FLOAT_EQ(c.b, srgb(30 / 255.0f));
  EXPECT_FLOAT_EQ(c.a, 1.0f);
  const vec4 g = make_texture_image(image8(1, 1, 2, {200, 50}), ColorEncoding::Linear).texel(0, 0);
  EXPECT_FLOAT_EQ(g.r, 200 / 255.0f);
  EXPECT_FLOAT_EQ(g.b, 200 / 255.0f);
  EXPECT_FLOAT_EQ(g.a, 50 / 255.0f);
}

// Each 4x4 block of 8-bit texels (64 bytes) is one cache line only if the storage starts on
// one: malloc's 16-byte alignment would split every block over two lines.
TEST(Texture, TexelBlocksStartOnCacheLines) {
  for (int size : {4, 5, 64, 300, 1024}) {
    const TextureImage bytes = make_texture_image(image8(size, size, 4, std::vector<std::uint8_t>(std::size_t(size) * size * 4, 7)),
                                                  ColorEncoding::Linear);
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(bytes.texels8.data()) % 64, 0u) << size;
    Image floats;
    floats.width = floats.height = size;
    floats.channels = 4;
    floats.bits_per_channel = 32;
    floats.pixels = std::make_shared<std::vector<std::uint8_t>>(std::size_t(size) * size * 16, 0);
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(make_texture_image(floats, ColorEncoding::Linear).texels_float.data()) % 64, 0u) << size;
  }
}

// A texture of 2 MiB or more starts on a huge page (2 MiB), so that the kernel can back
// the whole pages inside it with huge pages; a smaller one on a cache line only. Its texels
// read back as written either way.
TEST(Texture, LargeTexturesStartOnHugePages) {
  for (int size : {700, 725, 1024}) {  // 1.87 MiB, 2.02 MiB (728^2 stored), 4 MiB of 8-bit texels
    const TextureImage bytes = make_texture_image(image8(size, size, 4, std::vector<std::uint8_t>(std::size_t(size) * size * 4, 7)),
                                                  ColorEncoding::Linear);
    const bool large = bytes.stored_bytes() >= (std::size_t{2} << 20);
    EXPECT_EQ(large, size != 700) << size;
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(bytes.texels8.data()) % (large ? std::size_t{2} << 20 : 64), 0u) << size;
    for (int c = 0; c < 4; ++c) EXPECT_FLOAT_EQ(bytes.texel(size - 1, size - 1)[c], 7.0f / 255.0f) << size;
  }
}

// Every channel count, at a size that is not a multiple of the 4x4 blocks: each texel read
// back is its row-major source expanded to RGBA (grey to RGB, alpha 1 when absent).
TEST(Texture, EveryChannelCountLandsEachTexelInItsBlock) {
  std::mt19937 rng(11);
  const int w = 7, h = 6;
  for (int nc = 1; nc <= 4; ++nc) {
    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(w) * h * nc);
    for (std::uint8_t& b : bytes) b = static_cast<std::uint8_t>(rng() & 0xff);
    const TextureImage tex = make_texture_image(image8(w, h, nc, bytes), ColorEncoding::Linear);
    for (int j = 0; j < h; ++j)
      for (int i = 0; i < w; ++i) {
        const std::uint8_t* p = &bytes[(static_cast<std::size_t>(j) * w + i) * nc];
        const bool grey = nc < 3, alpha = nc == 2 || nc == 4;
        const int want[4] = {p[0], grey ? p[0] : p[1], grey ? p[0] : p[2], alpha ? p[nc - 1] : 255};
        const vec4 got = tex.texel(i, j);
        for (int c = 0; c < 4; ++c)
          EXPECT_EQ(std::lround(got[c] * 255.0f), want[c]) << nc << " channels, texel " << i << "," << j << " channel " << c;
      }
  }
}

}  // namespace
}  // namespace tessera
