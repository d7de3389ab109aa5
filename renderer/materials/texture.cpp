#include "renderer/materials/texture.h"

#include <array>
#include <cstring>
#include <type_traits>

#include <emmintrin.h>

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
      if ((n & (n - 1)) == 0) return i & (n - 1);  // a power of two: the same, without a division
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

// The linear RGBA of the texel stored at `at`, in SSE2 (both builds: the same bits as scalar
// code, one multiplication per value), inlined into the lookups below. A bilinear lookup's
// four texels were 16 conversions and 32 multiplications one by one.
[[gnu::always_inline]] inline __m128 decode_texel(const TextureImage& image, std::size_t at) {
  if (image.texels8.empty()) return _mm_loadu_ps(&image.texels_float[at].x);
  const std::array<std::uint8_t, 4>& t = image.texels8[at];
  constexpr float kInv255 = 1.0f / 255.0f;
  if (image.encoding == ColorEncoding::SRGB)
    return _mm_setr_ps(kSrgbTable[t[0]], kSrgbTable[t[1]], kSrgbTable[t[2]], t[3] * kInv255);
  std::int32_t bytes;
  std::memcpy(&bytes, t.data(), 4);
  const __m128i zero = _mm_setzero_si128();
  const __m128i words = _mm_unpacklo_epi16(_mm_unpacklo_epi8(_mm_cvtsi32_si128(bytes), zero), zero);
  return _mm_mul_ps(_mm_cvtepi32_ps(words), _mm_set1_ps(kInv255));
}

vec4 to_vec4(__m128 v) {
  vec4 out;
  _mm_storeu_ps(&out.x, v);
  return out;
}

vec2 transform_uv(const TextureTransform& t, vec2 uv) {
  if (t.rotation == 0.0f && t.scale == vec2(1.0f) && t.offset == vec2(0.0f)) return uv;
  // KHR_texture_transform: uv' = T * R * S * uv, with R rotating counter-clockwise in UV space.
  const float c = std::cos(t.rotation), s = std::sin(t.rotation);
  const vec2 scaled = uv * t.scale;
  return vec2(c * scaled.x + s * scaled.y, -s * scaled.x + c * scaled.y) + t.offset;
}

// A texel of NC channels (grey, grey+alpha, RGB or RGBA) as RGBA; value(k) reads channel k.
template <int NC, typename T, typename Value>
std::array<T, 4> rgba(const Value& value, T one) {
  if constexpr (NC == 1) return {value(0), value(0), value(0), one};
  else if constexpr (NC == 2) return {value(0), value(0), value(0), value(1)};
  else if constexpr (NC == 3) return {value(0), value(1), value(2), one};
  else return {value(0), value(1), value(2), value(3)};
}

// Every texel of an NC-channel image, rows in parallel (a 2048^2 texture is 4 M texels), each
// row's place in the 4x4 blocks found once: store(at, rgba) with channel i read by read(i).
template <int NC, typename T, typename Read, typename Store>
void convert_texels(const Image& image, const TextureImage& out, T one, const Read& read, const Store& store) {
  constexpr int kB = TextureImage::kBlock;
  tbb::parallel_for(tbb::blocked_range<int>(0, image.height, 32), [&](const tbb::blocked_range<int>& rows) {
    const unsigned width = image.width;  // a local: stores of bytes may alias `image`, not it
    for (int j = rows.begin(); j != rows.end(); ++j) {
      const std::size_t row = out.index(0, j);
      std::size_t p = static_cast<std::size_t>(j) * width * NC;  // the texel's first channel
      for (unsigned i = 0; i < width; ++i, p += NC)
        store(row + (i / kB) * kB * kB + i % kB, rgba<NC>([&](int k) { return read(p + k); }, one));
    }
  });
}

// convert(std::integral_constant<int, NC>) for the image's channel count NC.
template <typename Convert>
void with_channel_count(int nc, const Convert& convert) {
  switch (nc) {
    case 1: return convert(std::integral_constant<int, 1>{});
    case 2: return convert(std::integral_constant<int, 2>{});
    case 3: return convert(std::integral_constant<int, 3>{});
    default: return convert(std::integral_constant<int, 4>{});
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
  if (image.bits_per_channel == 8) {
    out.texels8.resize(stored);
    const std::uint8_t* px = image.pixels->data();
    std::array<std::uint8_t, 4>* texels = out.texels8.data();  // a local pointer: stores of bytes may alias `out`
    with_channel_count(image.channels, [&](auto nc) {
      convert_texels<decltype(nc)::value>(image, out, std::uint8_t{255}, [px](std::size_t i) { return px[i]; },
                                          [texels](std::size_t at, const std::array<std::uint8_t, 4>& t) { texels[at] = t; });
    });
    return out;
  }
  out.texels_float.resize(stored);
  with_channel_count(image.channels, [&](auto nc) {
    convert_texels<decltype(nc)::value>(
        image, out, 1.0f, [&](std::size_t i) { return channel(image, i); },
        [&](std::size_t at, const std::array<float, 4>& t) {
          vec4 c(t[0], t[1], t[2], t[3]);
          if (encoding == ColorEncoding::SRGB)
            for (int k = 0; k < 3; ++k) c[k] = srgb_to_linear(c[k]);
          out.texels_float[at] = c;
        });
  });
  return out;
}

vec4 TextureImage::texel(int i, int j) const { return to_vec4(decode_texel(*this, index(i, j))); }

TexelQuad locate_texels(const TextureImage& image, const TextureRef& ref, vec2 uv) {
  TexelQuad q;
  uv = transform_uv(ref.transform, uv);
  if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) uv = vec2(0.0f);
  // Keep coordinates in int range before flooring; wrapping makes far values equivalent
  // (fmod returns smaller values unchanged: it is skipped for them, a division saved).
  auto in_range = [](float v) { return std::fabs(v) < 0x1p24f ? v : std::fmod(v, 0x1p24f); };
  const float x = in_range(uv.x * image.width - 0.5f), y = in_range(uv.y * image.height - 0.5f);
  // floor(), exact below 2^24 (the generic x86-64 build has no instruction for it).
  const int i = static_cast<int>(x) - (x < static_cast<int>(x)), j = static_cast<int>(y) - (y < static_cast<int>(y));
  q.dx = x - static_cast<float>(i);
  q.dy = y - static_cast<float>(j);
  // Inside the image every wrap mode is the identity: only texels past an edge are wrapped.
  auto column = [&](int c) { return c >= 0 && c < image.width ? c : wrap(c, image.width, ref.wrap_s); };
  auto row = [&](int r) { return r >= 0 && r < image.height ? r : wrap(r, image.height, ref.wrap_t); };
  if (ref.filter == FilterMode::Nearest) {
    q.at[0] = q.at[1] = q.at[2] = q.at[3] = image.index(column(i + (q.dx >= 0.5f)), row(j + (q.dy >= 0.5f)));
    return q;
  }
  const int i0 = column(i), i1 = column(i + 1), j0 = row(j), j1 = row(j + 1);
  q.at[0] = image.index(i0, j0);
  q.at[1] = image.index(i1, j0);
  q.at[2] = image.index(i0, j1);
  q.at[3] = image.index(i1, j1);
  return q;
}

vec4 read_texels(const TextureImage& image, FilterMode filter, const TexelQuad& q) {
  if (filter == FilterMode::Nearest) return to_vec4(decode_texel(image, q.at[0]));
  const float dx = q.dx, dy = q.dy;
  const float weights[4] = {(1 - dx) * (1 - dy), dx * (1 - dy), (1 - dx) * dy, dx * dy};
  __m128 sum = _mm_mul_ps(_mm_set1_ps(weights[0]), decode_texel(image, q.at[0]));
  for (int k = 1; k < 4; ++k) sum = _mm_add_ps(sum, _mm_mul_ps(_mm_set1_ps(weights[k]), decode_texel(image, q.at[k])));
  return to_vec4(sum);
}

void prefetch_texels(const TextureImage& image, const TexelQuad& q) {
  for (std::size_t at : q.at) {
    if (image.texels8.empty()) __builtin_prefetch(&image.texels_float[at]);
    else __builtin_prefetch(&image.texels8[at]);
  }
}

vec4 sample_texture(const TextureImage& image, const TextureRef& ref, vec2 uv) {
  return read_texels(image, ref.filter, locate_texels(image, ref, uv));
}

bool same_sampling(const TextureImage& a, const TextureRef& ra, const TextureImage& b, const TextureRef& rb) {
  const TextureTransform &ta = ra.transform, &tb = rb.transform;
  return a.width == b.width && a.height == b.height && ra.texcoord == rb.texcoord && ra.wrap_s == rb.wrap_s &&
         ra.wrap_t == rb.wrap_t && ra.filter == rb.filter && same_bits(ta.offset.x, tb.offset.x) &&
         same_bits(ta.offset.y, tb.offset.y) && same_bits(ta.rotation, tb.rotation) &&
         same_bits(ta.scale.x, tb.scale.x) && same_bits(ta.scale.y, tb.scale.y);
}

}  // namespace tessera
