// Planar float images: one contiguous plane per channel, so per-row loops vectorise.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

namespace tessera::denoiser {

struct Planes {
  int width = 0, height = 0, channels = 0;
  std::vector<float> data;  // channel c, pixel i at data[c * width * height + i]

  Planes() = default;
  Planes(int w, int h, int c, float value = 0.0f)
      : width(w), height(h), channels(c), data(static_cast<std::size_t>(w) * h * c, value) {}
  std::size_t pixels() const { return static_cast<std::size_t>(width) * height; }
  float* plane(int c) { return data.data() + c * pixels(); }
  const float* plane(int c) const { return data.data() + c * pixels(); }
  float& at(int c, std::size_t i) { return data[c * pixels() + i]; }
  float at(int c, std::size_t i) const { return data[c * pixels() + i]; }
};

// Interleaved (`stride` floats per pixel) to planar, non-finite values replaced by 0.
Planes to_planes(const std::vector<float>& interleaved, int width, int height, int stride);

// Stacks the channels of several images (all the same size) into one.
Planes stack(const std::vector<const Planes*>& parts);

// Mean over the (2 r + 1)^2 box clipped to the image, over the pixels whose `mask` is 1
// (0 or 1 per pixel; null: all). Pixels whose box holds none get 0. Separable, O(1) per pixel in r.
Planes box_mean(const Planes& in, int r, const std::vector<float>* mask = nullptr);

// Fast exp for x <= 0 (the NL-means weights): relative error below 3e-7 + 1e-7 |x| down to -87,
// exactly 0 below (and for NaN). Branch-free, so loops over it vectorise; deterministic.
inline float exp_neg(float x) {
  const bool zero = !(x >= -87.0f);
  const float t = (zero ? -87.0f : x) * 1.44269504f;  // x log2(e), in [-125.6, 0]
  const int n = static_cast<int>(t - 0.5f);  // the nearest integer (t <= 0)
  const float u = (t - static_cast<float>(n)) * 0.69314718f;  // 2^(t - n) = e^u, |u| <= ln(2) / 2
  const float p = 1.0f + u * (1.0f + u * (0.5f + u * (1.0f / 6 + u * (1.0f / 24 + u * (1.0f / 120 + u * (1.0f / 720))))));
  const std::int32_t bits = (n + 127) << 23;  // 2^n, n >= -126: a normal float
  float scale;
  std::memcpy(&scale, &bits, sizeof scale);
  return zero ? 0.0f : p * scale;
}

}  // namespace tessera::denoiser
