// Textures decoded once into linear float RGBA, sampled with glTF sampler state.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "renderer/util/cache_line_allocator.h"
#include "renderer/util/math.h"
#include "renderer/description/scene.h"

namespace tessera {

enum class ColorEncoding { Linear, SRGB };

// 8-bit images stay 8-bit RGBA (a quarter of the memory of floats) and are decoded through
// a 256-entry table at lookup; 16-bit and float images are stored as linear float RGBA.
// Texels are stored in 4x4 blocks (an 8-bit block is one 64-byte cache line): a bilinear
// lookup's four texels then share one block 9 times in 16, where rows of a 2048-wide image
// put them in two lines 8 KiB apart. DamagedHelmet's textures were a quarter of its render.
struct TextureImage {
  static constexpr int kBlock = 4;
  int width = 0, height = 0;
  int blocks_x = 0;  // blocks per block row
  ColorEncoding encoding = ColorEncoding::Linear;
  // By block, block rows top first; every block starts a cache line. Texels of the last
  // block column and row beyond the image are never written nor read.
  std::vector<std::array<std::uint8_t, 4>, CacheLineAllocator<std::array<std::uint8_t, 4>>> texels8;
  std::vector<vec4, CacheLineAllocator<vec4>> texels_float;  // linear, when the source has more than 8 bits

  bool empty() const { return width == 0; }
  std::size_t stored_bytes() const { return texels8.size() * sizeof(texels8[0]) + texels_float.size() * sizeof(vec4); }
  std::size_t index(int i, int j) const {  // texel (column i, row j from the top; both >= 0)
    const unsigned u = static_cast<unsigned>(i), v = static_cast<unsigned>(j);  // shifts and masks
    const std::size_t block = static_cast<std::size_t>(v / kBlock) * blocks_x + u / kBlock;
    return block * (kBlock * kBlock) + (v % kBlock) * kBlock + u % kBlock;
  }
  vec4 texel(int i, int j) const;  // linear RGBA; 0 <= i < width, 0 <= j < height
};

// Converts a decoded image; SRGB decodes the RGB channels with the sRGB transfer function
// (alpha is always linear), as glTF requires for baseColor and emissive textures.
TextureImage make_texture_image(const Image& image, ColorEncoding encoding);

// Where a lookup at uv reads: the bilinear's four texels (or the nearest one, in at[0]) and
// the weights' fractions. The same in every image of one size under one sampler
// (same_sampling), so a material whose maps share those finds it once per hit.
struct TexelQuad {
  std::size_t at[4];
  float dx, dy;
};
// Wrap modes and KHR_texture_transform applied.
TexelQuad locate_texels(const TextureImage& image, const TextureRef& ref, vec2 uv);
// The bilinear (or nearest) lookup at q.
vec4 read_texels(const TextureImage& image, FilterMode filter, const TexelQuad& q);
// Starts loading the texels read_texels(image, ..., q) will read. Called for each of a hit's
// textures before the first lookup, it overlaps their cache misses, which otherwise come one
// after the other (each lookup waits for its texels before the next one starts).
void prefetch_texels(const TextureImage& image, const TexelQuad& q);
// read_texels at locate_texels.
vec4 sample_texture(const TextureImage& image, const TextureRef& ref, vec2 uv);
// Lookups through ra in a and through rb in b read the same places at every uv.
bool same_sampling(const TextureImage& a, const TextureRef& ra, const TextureImage& b, const TextureRef& rb);

float srgb_to_linear(float v);

}  // namespace tessera
