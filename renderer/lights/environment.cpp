#include "renderer/lights/environment.h"

#include <algorithm>
#include <stdexcept>

namespace tessera {

Environment::Environment(const EnvironmentParams& params)
    : background_(params.background), scale_(params.scale) {
  const float rot = glm::radians(params.rotate_degrees);
  cos_rot_ = std::cos(rot);
  sin_rot_ = std::sin(rot);
  if (!params.image) return;
  const FloatImage& img = *params.image;
  const std::vector<float>& pixels = img.pixels;
  width_ = img.width;
  height_ = img.height;
  texels_.resize(static_cast<std::size_t>(width_) * height_);
  const int nc = img.channels;
  for (std::size_t i = 0; i < texels_.size(); ++i) {
    vec3 c = nc >= 3 ? vec3(pixels[i * nc], pixels[i * nc + 1], pixels[i * nc + 2]) : vec3(pixels[i * nc]);
    // Negative or non-finite texels would poison every estimate that sees them.
    for (int k = 0; k < 3; ++k) c[k] = std::isfinite(c[k]) && c[k] > 0.0f ? c[k] : 0.0f;
    texels_[i] = c;
  }
  build_distribution();
}

void Environment::build_distribution() {
  // Weight of a texel: the brightest luminance that bilinear lookups inside it can return
  // (its 3x3 neighbourhood; otherwise a bright texel's filtered halo would be sampled with
  // the dim neighbours' low density: fireflies), times the solid angle it covers (sin theta
  // at its row centre), with a floor so that every direction keeps a non-zero density.
  auto lum = [&](int x, int y) {
    x = (x % width_ + width_) % width_;
    y = std::clamp(y, 0, height_ - 1);
    return luminance(texels_[std::size_t(y) * width_ + x]);
  };
  std::vector<double> row_weights(height_);
  columns_.reserve(height_);
  for (int y = 0; y < height_; ++y) {
    const double sin_theta = std::sin(kPi * (y + 0.5) / height_);
    std::vector<double> w(width_);
    for (int x = 0; x < width_; ++x) {
      float peak = 0.0f;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) peak = fmax_inline(peak, lum(x + dx, y + dy));
      w[x] = (peak + 1e-4) * sin_theta;
    }
    columns_.emplace_back(std::move(w));
    row_weights[y] = columns_.back().total();
  }
  rows_ = Distribution1D(std::move(row_weights));
}

vec3 Environment::uv_to_direction(const vec2& uv) const {
  // sin and cos of the polar angle both from v: sqrt(1 - y^2) loses digits near the poles.
  const float phi = (uv.x - 0.5f) * 2.0f * kPi, y = std::cos(kPi * uv.y), r = std::sin(kPi * uv.y);
  const float xr = r * std::cos(phi), zr = r * std::sin(phi);  // in the map's frame
  return {cos_rot_ * xr + sin_rot_ * zr, y, -sin_rot_ * xr + cos_rot_ * zr};
}

vec3 Environment::sample(const vec2& u, float& pdf) const {
  float dy, dx;
  const std::size_t row = rows_.sample(u.y, &dy);
  const std::size_t col = columns_[row].sample(u.x, &dx);
  const vec2 uv((col + dx) / width_, (row + dy) / height_);
  const float sin_theta = std::sin(kPi * uv.y);
  // Density over uv is pmf(row) pmf(col | row) * width * height; d omega = 2 pi^2 sin(theta) du dv.
  const float pdf_uv = rows_.pmf(row) * columns_[row].pmf(col) * float(width_) * float(height_);
  pdf = sin_theta > 0.0f ? pdf_uv / (2.0f * kPi * kPi * sin_theta) : 0.0f;
  return uv_to_direction(uv);
}

float Environment::pdf(const vec3& direction) const {
  const vec2 uv = direction_to_uv(direction);
  const int col = std::clamp(static_cast<int>(uv.x * width_), 0, width_ - 1);
  const int row = std::clamp(static_cast<int>(uv.y * height_), 0, height_ - 1);
  const float sin_theta = std::hypot(direction.x, direction.z) / glm::length(direction);
  if (!(sin_theta > 0.0f)) return 0.0f;
  const float pdf_uv = rows_.pmf(row) * columns_[row].pmf(col) * float(width_) * float(height_);
  return pdf_uv / (2.0f * kPi * kPi * sin_theta);
}

vec2 Environment::direction_to_uv(const vec3& d) const {
  // Rotate the world direction into the map's frame (the map turns by +rotate about +Y).
  const float x = cos_rot_ * d.x - sin_rot_ * d.z, z = sin_rot_ * d.x + cos_rot_ * d.z;
  const float u = 0.5f + std::atan2(z, x) * (0.5f * kInvPi);
  const float v = 0.5f - std::asin(glm::clamp(d.y, -1.0f, 1.0f)) * kInvPi;
  return {u, v};
}

vec3 Environment::radiance(const vec3& direction) const {
  if (width_ == 0) return background_;
  const vec2 uv = direction_to_uv(direction);
  // Bilinear: wrap in u (longitude), clamp in v (latitude).
  const float x = uv.x * width_ - 0.5f, y = glm::clamp(uv.y * height_ - 0.5f, 0.0f, height_ - 1.0f);
  const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(y);
  const float fx = x - x0, fy = y - y0;
  const int y1 = std::min(y0 + 1, height_ - 1);
  auto at = [&](int i, int j) { return texels_[static_cast<std::size_t>(j) * width_ + ((i % width_) + width_) % width_]; };
  const vec3 c = (1 - fx) * (1 - fy) * at(x0, y0) + fx * (1 - fy) * at(x0 + 1, y0) +
                 (1 - fx) * fy * at(x0, y1) + fx * fy * at(x0 + 1, y1);
  return c * scale_;
}

}  // namespace tessera
