#include "renderer/texture.h"

#include <array>
#include <cstring>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace tessera {

float srgb_to_linear(float v) {
  return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

namespace {

float channel(const Image& img, std::size_t i) {
  const std::uint8_t* px = img.pixels->data();
  switch (img.bits_per_channel) {
    case 8: return px[i] / 255.0f;
    case 16: {
      std::uint16_t v;
      std::memcpy(&v, &px[2 * i], 2);
      return v / 65535.0f;
    }
    default: {
      float v;
      std::memcpy(&v, &px[4 * i], 4);
      return std::isfinite(v) ? v : 0.0f;
    }
  }
}

int wrap(int i, int n, WrapMode mode) {
  switch (mode) {
    case WrapMode::ClampToEdge: return i < 0 ? 0 : (i >= n ? n - 1 : i);
    case WrapMode::MirroredRepeat: {
      const int period = 2 * n;
      int m = i % period;
      if (m < 0) m += period;
      return m < n ? m : period - 1 - m;
    }
    default: {
      const int m = i % n;
      return m < 0 ? m + n : m;
    }
  }
}

vec2 transform_uv(const TextureTransform& t, vec2 uv) {
  if (t.rotation == 0.0f && t.scale == vec2(1.0f) && t.offset == vec2(0.0f)) return uv;
  // KHR_texture_transform: uv' = T * R * S * uv, with R rotating counter-clockwise in UV space.
  const float c = std::cos(t.rotation), s = std::sin(t.rotation);
  const vec2 scaled = uv * t.scale;
  return vec2(c * scaled.x + s * scaled.y, -s * scaled.x + c * scaled.y) + t.offset;
}

}  // namespace

TextureImage make_texture_image(const Image& image, ColorEncoding encoding) {
  TextureImage out;
  out.width = image.width;
  out.height = image.height;
  out.encoding = encoding;
  const std::size_t n = static_cast<std::size_t>(image.width) * image.height;
  const int nc = image.channels;
  auto expand = [nc](auto&& value, std::size_t p, auto one) {  // grey, grey+alpha, RGB -> RGBA
    using T = decltype(one);
    const T g = value(p * nc);
    if (nc == 1) return std::array<T, 4>{g, g, g, one};
    if (nc == 2) return std::array<T, 4>{g, g, g, value(p * nc + 1)};
    return std::array<T, 4>{g, value(p * nc + 1), value(p * nc + 2), nc == 4 ? value(p * nc + 3) : one};
  };
  // Blocks of texels in parallel: a 2048^2 texture is 4 M of them.
  auto each_texel = [n](auto&& convert) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1 << 16), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t p = r.begin(); p != r.end(); ++p) convert(p);
    });
  };
  if (image.bits_per_channel == 8 && nc == 4) {  // already RGBA: shared, not copied
    out.texels8 = image.pixels;
    out.rgba8 = out.texels8->data();
    return out;
  }
  if (image.bits_per_channel == 8) {
    auto rgba = std::make_shared<std::vector<std::uint8_t>>(4 * n);
    auto byte = [&](std::size_t i) { return (*image.pixels)[i]; };
    each_texel([&](std::size_t p) {
      const std::array<std::uint8_t, 4> t = expand(byte, p, std::uint8_t{255});
      std::memcpy(&(*rgba)[4 * p], t.data(), 4);
    });
    out.rgba8 = rgba->data();
    out.texels8 = std::move(rgba);
    return out;
  }
  out.texels_float.resize(n);
  auto value = [&](std::size_t i) { return channel(image, i); };
  each_texel([&](std::size_t p) {
    const std::array<float, 4> t = expand(value, p, 1.0f);
    vec4 c(t[0], t[1], t[2], t[3]);
    if (encoding == ColorEncoding::SRGB)
      for (int k = 0; k < 3; ++k) c[k] = srgb_to_linear(c[k]);
    out.texels_float[p] = c;
  });
  return out;
}

vec4 TextureImage::texel(std::size_t index) const {
  if (!rgba8) return texels_float[index];
  static const std::array<float, 256> kSrgb = [] {
    std::array<float, 256> t;
    for (int i = 0; i < 256; ++i) t[i] = srgb_to_linear(i / 255.0f);
    return t;
  }();
  const std::uint8_t* t = rgba8 + 4 * index;
  constexpr float kInv255 = 1.0f / 255.0f;
  if (encoding == ColorEncoding::SRGB) return {kSrgb[t[0]], kSrgb[t[1]], kSrgb[t[2]], t[3] * kInv255};
  return {t[0] * kInv255, t[1] * kInv255, t[2] * kInv255, t[3] * kInv255};
}

vec4 sample_texture(const TextureImage& image, const TextureRef& ref, vec2 uv) {
  uv = transform_uv(ref.transform, uv);
  if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) uv = vec2(0.0f);
  const float x = uv.x * image.width - 0.5f, y = uv.y * image.height - 0.5f;
  auto texel = [&](int i, int j) {
    return image.texel(static_cast<std::size_t>(wrap(j, image.height, ref.wrap_t)) * image.width +
                       wrap(i, image.width, ref.wrap_s));
  };
  // Keep coordinates in int range before flooring; wrapping makes far values equivalent.
  const float fx = std::floor(std::fmod(x, 1 << 24)), fy = std::floor(std::fmod(y, 1 << 24));
  const float dx = std::fmod(x, 1 << 24) - fx, dy = std::fmod(y, 1 << 24) - fy;
  const int i = static_cast<int>(fx), j = static_cast<int>(fy);
  if (ref.filter == FilterMode::Nearest) return texel(i + (dx >= 0.5f), j + (dy >= 0.5f));
  return (1 - dx) * (1 - dy) * texel(i, j) + dx * (1 - dy) * texel(i + 1, j) +
         (1 - dx) * dy * texel(i, j + 1) + dx * dy * texel(i + 1, j + 1);
}

}  // namespace tessera
