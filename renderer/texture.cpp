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

// Every byte's sRGB decode, made once at start: a lookup is then one load per channel.
const std::array<float, 256> kSrgbTable = [] {
  std::array<float, 256> t;
  for (int k = 0; k < 256; ++k) t[k] = srgb_to_linear(k / 255.0f);
  return t;
}();

// The linear RGBA of the texel stored at `at` (inlined into the lookups below).
[[gnu::always_inline]] inline vec4 decode_texel(const TextureImage& image, std::size_t at) {
  if (image.texels8.empty()) return image.texels_float[at];
  const std::array<std::uint8_t, 4>& t = image.texels8[at];
  constexpr float kInv255 = 1.0f / 255.0f;
  if (image.encoding == ColorEncoding::SRGB) return {kSrgbTable[t[0]], kSrgbTable[t[1]], kSrgbTable[t[2]], t[3] * kInv255};
  return {t[0] * kInv255, t[1] * kInv255, t[2] * kInv255, t[3] * kInv255};
}

vec2 transform_uv(const TextureTransform& t, vec2 uv) {
  if (t.rotation == 0.0f && t.scale == vec2(1.0f) && t.offset == vec2(0.0f)) return uv;
  // KHR_texture_transform: uv' = T * R * S * uv, with R rotating counter-clockwise in UV space.
  const float c = std::cos(t.rotation), s = std::sin(t.rotation);
  const vec2 scaled = uv * t.scale;
  return vec2(c * scaled.x + s * scaled.y, -s * scaled.x + c * scaled.y) + t.offset;
}

using Texel8 = std::array<std::uint8_t, 4>;

// One row of 8-bit texels with NC channels into its place in 4x4 blocks (dst: the row's
// first texel; texel i of the row is kBlock * kBlock apart per block, then consecutive).
template <int NC>
void copy_row8(const std::uint8_t* src, Texel8* dst, int width) {
  constexpr int kB = TextureImage::kBlock;
  for (int i = 0; i < width; ++i, src += NC) {
    Texel8& t = dst[(i / kB) * kB * kB + i % kB];
    if constexpr (NC == 1) t = {src[0], src[0], src[0], 255};
    if constexpr (NC == 2) t = {src[0], src[0], src[0], src[1]};
    if constexpr (NC == 3) t = {src[0], src[1], src[2], 255};
    if constexpr (NC == 4) t = {src[0], src[1], src[2], src[3]};
  }
}

}  // namespace

TextureImage make_texture_image(const Image& image, ColorEncoding encoding) {
  TextureImage out;
  out.width = image.width;
  out.height = image.height;
  out.encoding = encoding;
  out.blocks_x = (image.width + TextureImage::kBlock - 1) / TextureImage::kBlock;
  const int blocks_y = (image.height + TextureImage::kBlock - 1) / TextureImage::kBlock;
  const std::size_t stored = static_cast<std::size_t>(out.blocks_x) * blocks_y * TextureImage::kBlock * TextureImage::kBlock;
  const int nc = image.channels;
  auto expand = [nc](auto&& value, std::size_t p, auto one) {  // grey, grey+alpha, RGB -> RGBA
    using T = decltype(one);
    const T g = value(p * nc);
    if (nc == 1) return std::array<T, 4>{g, g, g, one};
    if (nc == 2) return std::array<T, 4>{g, g, g, value(p * nc + 1)};
    return std::array<T, 4>{g, value(p * nc + 1), value(p * nc + 2), nc == 4 ? value(p * nc + 3) : one};
  };
  // Rows of texels in parallel: a 2048^2 texture is 4 M of them. p is the source's row-major
  // index, `at` where the texel is stored.
  auto each_texel = [&](auto&& convert) {
    tbb::parallel_for(tbb::blocked_range<int>(0, image.height, 32), [&](const tbb::blocked_range<int>& rows) {
      for (int j = rows.begin(); j != rows.end(); ++j)
        for (int i = 0; i < image.width; ++i) convert(static_cast<std::size_t>(j) * image.width + i, out.index(i, j));
    });
  };
  if (image.bits_per_channel == 8) {
    out.texels8.resize(stored);
    tbb::parallel_for(tbb::blocked_range<int>(0, image.height, 32), [&](const tbb::blocked_range<int>& rows) {
      for (int j = rows.begin(); j != rows.end(); ++j) {
        const std::uint8_t* src = image.pixels->data() + static_cast<std::size_t>(j) * image.width * nc;
        Texel8* dst = &out.texels8[out.index(0, j)];
        switch (nc) {
          case 1: copy_row8<1>(src, dst, image.width); break;
          case 2: copy_row8<2>(src, dst, image.width); break;
          case 3: copy_row8<3>(src, dst, image.width); break;
          default: copy_row8<4>(src, dst, image.width); break;
        }
      }
    });
    return out;
  }
  out.texels_float.resize(stored);
  auto value = [&](std::size_t i) { return channel(image, i); };
  each_texel([&](std::size_t p, std::size_t at) {
    const std::array<float, 4> t = expand(value, p, 1.0f);
    vec4 c(t[0], t[1], t[2], t[3]);
    if (encoding == ColorEncoding::SRGB)
      for (int k = 0; k < 3; ++k) c[k] = srgb_to_linear(c[k]);
    out.texels_float[at] = c;
  });
  return out;
}

vec4 TextureImage::texel(int i, int j) const { return decode_texel(*this, index(i, j)); }

vec4 sample_texture(const TextureImage& image, const TextureRef& ref, vec2 uv) {
  uv = transform_uv(ref.transform, uv);
  if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) uv = vec2(0.0f);
  // Keep coordinates in int range before flooring; wrapping makes far values equivalent
  // (fmod returns smaller values unchanged: it is skipped for them, a division saved).
  auto in_range = [](float v) { return std::fabs(v) < 0x1p24f ? v : std::fmod(v, 0x1p24f); };
  const float x = in_range(uv.x * image.width - 0.5f), y = in_range(uv.y * image.height - 0.5f);
  const float fx = std::floor(x), fy = std::floor(y);
  const float dx = x - fx, dy = y - fy;
  const int i = static_cast<int>(fx), j = static_cast<int>(fy);
  // Inside the image every wrap mode is the identity: only texels past an edge are wrapped.
  auto column = [&](int c) { return c >= 0 && c < image.width ? c : wrap(c, image.width, ref.wrap_s); };
  auto row = [&](int r) { return r >= 0 && r < image.height ? r : wrap(r, image.height, ref.wrap_t); };
  if (ref.filter == FilterMode::Nearest)
    return decode_texel(image, image.index(column(i + (dx >= 0.5f)), row(j + (dy >= 0.5f))));
  const int i0 = column(i), i1 = column(i + 1), j0 = row(j), j1 = row(j + 1);
  return (1 - dx) * (1 - dy) * decode_texel(image, image.index(i0, j0)) +
         dx * (1 - dy) * decode_texel(image, image.index(i1, j0)) +
         (1 - dx) * dy * decode_texel(image, image.index(i0, j1)) + dx * dy * decode_texel(image, image.index(i1, j1));
}

}  // namespace tessera
