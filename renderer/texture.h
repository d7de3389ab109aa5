// Textures decoded once into linear float RGBA, sampled with glTF sampler state.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "renderer/math.h"
#include "renderer/scene/scene.h"

namespace tessera {

enum class ColorEncoding { Linear, SRGB };

// 8-bit images stay 8-bit RGBA (a quarter of the memory of floats, and no copy at all when
// the image is RGBA) and are decoded through a 256-entry table at lookup; 16-bit and float
// images are stored as linear float RGBA.
struct TextureImage {
  int width = 0, height = 0;
  ColorEncoding encoding = ColorEncoding::Linear;
  // 8-bit: RGBA bytes, row-major, top row first; the scene image's own buffer when that is
  // RGBA already (every decoded JPEG, PNG and WebP), else a converted copy. rgba8 = its data.
  std::shared_ptr<const std::vector<std::uint8_t>> texels8;
  const std::uint8_t* rgba8 = nullptr;
  std::vector<vec4> texels_float;  // linear, when the source has more than 8 bits

  bool empty() const { return width == 0; }
  vec4 texel(std::size_t index) const;  // linear RGBA
};

// Converts a decoded image; SRGB decodes the RGB channels with the sRGB transfer function
// (alpha is always linear), as glTF requires for baseColor and emissive textures.
TextureImage make_texture_image(const Image& image, ColorEncoding encoding);

// Bilinear (or nearest) lookup with wrap modes and KHR_texture_transform.
vec4 sample_texture(const TextureImage& image, const TextureRef& ref, vec2 uv);

float srgb_to_linear(float v);

}  // namespace tessera
