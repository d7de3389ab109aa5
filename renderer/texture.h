// Textures decoded once into linear float RGBA, sampled with glTF sampler state.
#pragma once

#include <vector>

#include "renderer/math.h"
#include "renderer/scene/scene.h"

namespace tessera {

struct TextureImage {
  int width = 0, height = 0;
  std::vector<vec4> texels;  // linear RGBA, row-major, top row first
};

enum class ColorEncoding { Linear, SRGB };

// Converts a decoded image; SRGB decodes the RGB channels with the sRGB transfer function
// (alpha is always linear), as glTF requires for baseColor and emissive textures.
TextureImage make_texture_image(const Image& image, ColorEncoding encoding);

// Bilinear (or nearest) lookup with wrap modes and KHR_texture_transform.
vec4 sample_texture(const TextureImage& image, const TextureRef& ref, vec2 uv);

float srgb_to_linear(float v);

}  // namespace tessera
