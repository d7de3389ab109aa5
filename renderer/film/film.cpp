#include "renderer/film/film.h"

#include <algorithm>
#include <limits>

namespace tessera {

FilmState FilmState::empty(int width, int height, AovSelection aovs, bool adaptive) {
  FilmState s;
  s.width = width;
  s.height = height;
  s.aovs = aovs;
  const std::size_t n = static_cast<std::size_t>(width) * height;
  s.radiance.assign(n, glm::dvec3(0.0));
  s.samples.assign(n, 0);
  if (aovs.albedo) s.albedo.assign(n, vec3(0.0f));
  if (aovs.normal) s.normal.assign(n, vec3(0.0f));
  if (aovs.depth) s.depth.assign(n, 0.0f);
  if (aovs.counts_hits()) s.hits.assign(n, 0);
  if (aovs.halves || adaptive) {
    s.radiance_odd.assign(n, glm::dvec3(0.0));
    if (aovs.albedo) s.albedo_odd.assign(n, vec3(0.0f));
    if (aovs.normal) s.normal_odd.assign(n, vec3(0.0f));
  }
  if (aovs.halves) s.radiance_sq.assign(n, glm::dvec3(0.0));
  if (adaptive) s.converged.assign(n, 0);
  return s;
}

Film::Film(int width, int height, AovSelection aovs, bool adaptive)
    : state_(FilmState::empty(width, height, aovs, adaptive)) {}

Film::Film(FilmState state) : state_(std::move(state)) {}

void Film::add(int x, int y, const PixelSums& p) {
  FilmState& s = state_;
  const std::size_t i = index(x, y);
  s.samples[i] += p.samples;
  s.radiance[i] += p.radiance;
  if (s.aovs.albedo) s.albedo[i] += p.albedo;
  if (s.aovs.normal) s.normal[i] += p.normal;
  if (s.aovs.depth) s.depth[i] += p.depth;
  if (s.aovs.counts_hits()) s.hits[i] += p.hits;
  if (s.keeps_odd()) {
    s.radiance_odd[i] += p.radiance_odd;
    if (s.aovs.albedo) s.albedo_odd[i] += p.albedo_odd;
    if (s.aovs.normal) s.normal_odd[i] += p.normal_odd;
  }
  if (!s.radiance_sq.empty()) s.radiance_sq[i] += p.radiance_sq;
}

std::uint32_t Film::min_samples() const {
  const auto& v = state_.samples;
  return v.empty() ? 0 : *std::min_element(v.begin(), v.end());
}

std::uint64_t samples_left(const FilmState& film, int spp) {
  std::uint64_t left = 0;
  for (std::size_t i = 0; i < film.pixel_count(); ++i) {
    const bool stopped = film.adaptive() && film.converged[i];
    if (!stopped && film.samples[i] < static_cast<std::uint32_t>(spp)) left += spp - film.samples[i];
  }
  return left;
}

std::uint64_t Film::converged_pixels() const {
  return static_cast<std::uint64_t>(std::count(state_.converged.begin(), state_.converged.end(), 1));
}

namespace {

// Means of n-vectors of sums: total / count, or (total - odd) / even count, or odd / odd count.
enum class Half { all, even, odd };

std::uint32_t count_of(std::uint32_t n, Half h) {
  return h == Half::all ? n : h == Half::odd ? n / 2 : n - n / 2;
}

template <typename V>
std::vector<float> means(const FilmState& s, const std::vector<V>& total, const std::vector<V>& odd, Half h) {
  const std::size_t n = s.pixel_count();
  std::vector<float> out(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t count = count_of(s.samples[i], h);
    if (count == 0) continue;  // no sample: black, as an unrendered pixel
    const V sum = h == Half::all ? total[i] : h == Half::odd ? odd[i] : total[i] - odd[i];
    const double inv = 1.0 / count;  // as the film always resolved: the same bits as before halves
    for (int c = 0; c < 3; ++c) out[3 * i + c] = static_cast<float>(static_cast<double>(sum[c]) * inv);
  }
  return out;
}

void resolve_halves(const FilmState& s, FrameImage& img) {
  img.rgb_even = means(s, s.radiance, s.radiance_odd, Half::even);
  img.rgb_odd = means(s, s.radiance, s.radiance_odd, Half::odd);
  if (s.aovs.albedo) {
    img.albedo_even = means(s, s.albedo, s.albedo_odd, Half::even);
    img.albedo_odd = means(s, s.albedo, s.albedo_odd, Half::odd);
  }
  if (s.aovs.normal) {
    img.normal_even = means(s, s.normal, s.normal_odd, Half::even);
    img.normal_odd = means(s, s.normal, s.normal_odd, Half::odd);
  }
}

// The variance of each pixel's mean, s^2 / n with s^2 = (sum x^2 - n mean^2) / (n - 1).
std::vector<float> mean_variances(const FilmState& s) {
  const std::size_t n = s.pixel_count();
  std::vector<float> out(3 * n, 0.0f);
  for (std::size_t i = 0; i < n; ++i) {
    const double count = s.samples[i];
    if (count < 2.0) continue;
    for (int c = 0; c < 3; ++c) {
      const double mean = s.radiance[i][c] / count;
      const double spread = std::max(0.0, s.radiance_sq[i][c] - count * mean * mean);  // >= 0 but for rounding
      out[3 * i + c] = static_cast<float>(spread / ((count - 1.0) * count));
    }
  }
  return out;
}

}  // namespace

FrameImage Film::resolve() const {
  const FilmState& s = state_;
  FrameImage img;
  img.width = s.width;
  img.height = s.height;
  img.samples_per_pixel = static_cast<int>(min_samples());
  img.rgb = means(s, s.radiance, s.radiance, Half::all);
  if (s.aovs.albedo) img.albedo = means(s, s.albedo, s.albedo, Half::all);
  if (s.aovs.normal) img.normal = means(s, s.normal, s.normal, Half::all);
  if (s.aovs.depth) {
    img.depth.resize(s.pixel_count());
    for (std::size_t i = 0; i < s.pixel_count(); ++i)
      img.depth[i] = s.hits[i] ? s.depth[i] / s.hits[i] : std::numeric_limits<float>::infinity();
  }
  if (s.aovs.coverage) {
    img.alpha.resize(s.pixel_count());
    for (std::size_t i = 0; i < s.pixel_count(); ++i)
      img.alpha[i] = s.samples[i] ? static_cast<float>(static_cast<double>(s.hits[i]) / s.samples[i]) : 0.0f;
  }
  if (s.aovs.halves) resolve_halves(s, img), img.rgb_variance = mean_variances(s);
  if (s.aovs.halves || s.adaptive()) img.pixel_samples = s.samples;
  return img;
}

}  // namespace tessera
