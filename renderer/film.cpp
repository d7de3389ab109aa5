#include "renderer/film.h"

#include <algorithm>

namespace tessera {

Film::Film(int width, int height, AovSelection aovs)
    : width_(width), height_(height), aovs_(aovs) {
  const std::size_t n = static_cast<std::size_t>(width) * height;
  radiance_.assign(n, glm::dvec3(0.0));
  samples_.assign(n, 0);
  if (aovs.albedo) albedo_.assign(n, vec3(0.0f));
  if (aovs.normal) normal_.assign(n, vec3(0.0f));
  if (aovs.depth) {
    depth_.assign(n, 0.0f);
    hits_.assign(n, 0);
  }
}

void Film::add(int x, int y, std::uint32_t samples, const glm::dvec3& radiance_sum,
               const vec3& albedo_sum, const vec3& normal_sum, float depth_sum, std::uint32_t hits) {
  const std::size_t i = static_cast<std::size_t>(y) * width_ + x;
  samples_[i] += samples;
  radiance_[i] += radiance_sum;
  if (aovs_.albedo) albedo_[i] += albedo_sum;
  if (aovs_.normal) normal_[i] += normal_sum;
  if (aovs_.depth) {
    depth_[i] += depth_sum;
    hits_[i] += hits;
  }
}

std::uint32_t Film::min_samples() const {
  return samples_.empty() ? 0 : *std::min_element(samples_.begin(), samples_.end());
}

FrameImage Film::resolve() const {
  FrameImage img;
  img.width = width_;
  img.height = height_;
  img.samples_per_pixel = static_cast<int>(min_samples());
  const std::size_t n = radiance_.size();
  auto inv = [&](std::size_t i) { return samples_[i] ? 1.0 / samples_[i] : 0.0; };
  img.rgb.resize(3 * n);
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) img.rgb[3 * i + c] = static_cast<float>(radiance_[i][c] * inv(i));
  auto average3 = [&](const std::vector<vec3>& sums, std::vector<float>& out) {
    out.resize(3 * n);
    for (std::size_t i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) out[3 * i + c] = static_cast<float>(sums[i][c] * inv(i));
  };
  if (aovs_.albedo) average3(albedo_, img.albedo);
  if (aovs_.normal) average3(normal_, img.normal);
  if (aovs_.depth) {
    img.depth.resize(n);
    for (std::size_t i = 0; i < n; ++i) img.depth[i] = hits_[i] ? depth_[i] / hits_[i] : 0.0f;
  }
  return img;
}

}  // namespace tessera
