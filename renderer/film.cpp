#include "renderer/film.h"

#include <algorithm>

namespace tessera {

FilmState FilmState::empty(int width, int height, AovSelection aovs) {
  FilmState s;
  s.width = width;
  s.height = height;
  s.aovs = aovs;
  const std::size_t n = static_cast<std::size_t>(width) * height;
  s.radiance.assign(n, glm::dvec3(0.0));
  s.samples.assign(n, 0);
  if (aovs.albedo) s.albedo.assign(n, vec3(0.0f));
  if (aovs.normal) s.normal.assign(n, vec3(0.0f));
  if (aovs.depth) {
    s.depth.assign(n, 0.0f);
    s.hits.assign(n, 0);
  }
  return s;
}

Film::Film(int width, int height, AovSelection aovs) : state_(FilmState::empty(width, height, aovs)) {}

Film::Film(FilmState state) : state_(std::move(state)) {}

void Film::add(int x, int y, std::uint32_t samples, const glm::dvec3& radiance_sum,
               const vec3& albedo_sum, const vec3& normal_sum, float depth_sum, std::uint32_t hits) {
  FilmState& s = state_;
  const std::size_t i = static_cast<std::size_t>(y) * s.width + x;
  s.samples[i] += samples;
  s.radiance[i] += radiance_sum;
  if (s.aovs.albedo) s.albedo[i] += albedo_sum;
  if (s.aovs.normal) s.normal[i] += normal_sum;
  if (s.aovs.depth) {
    s.depth[i] += depth_sum;
    s.hits[i] += hits;
  }
}

std::uint32_t Film::min_samples() const {
  const auto& v = state_.samples;
  return v.empty() ? 0 : *std::min_element(v.begin(), v.end());
}

FrameImage Film::resolve() const {
  const FilmState& s = state_;
  FrameImage img;
  img.width = s.width;
  img.height = s.height;
  img.samples_per_pixel = static_cast<int>(min_samples());
  const std::size_t n = s.radiance.size();
  auto inv = [&](std::size_t i) { return s.samples[i] ? 1.0 / s.samples[i] : 0.0; };
  img.rgb.resize(3 * n);
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) img.rgb[3 * i + c] = static_cast<float>(s.radiance[i][c] * inv(i));
  auto average3 = [&](const std::vector<vec3>& sums, std::vector<float>& out) {
    out.resize(3 * n);
    for (std::size_t i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) out[3 * i + c] = static_cast<float>(sums[i][c] * inv(i));
  };
  if (s.aovs.albedo) average3(s.albedo, img.albedo);
  if (s.aovs.normal) average3(s.normal, img.normal);
  if (s.aovs.depth) {
    img.depth.resize(n);
    for (std::size_t i = 0; i < n; ++i) img.depth[i] = s.hits[i] ? s.depth[i] / s.hits[i] : 0.0f;
  }
  return img;
}

}  // namespace tessera
