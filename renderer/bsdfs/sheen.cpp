#include "renderer/bsdfs/sheen.h"

#include <array>

namespace tessera {
namespace {

constexpr int kCos = 32, kAlpha = 32;

// E(mu, alpha) on a grid of cos theta in (0,1] and alpha in [kMinSheenAlpha, 1], by
// midpoint quadrature over the hemisphere (the lobe is broad: 64 x 64 points suffice).
std::array<float, kCos * kAlpha> build_table() {
  std::array<float, kCos * kAlpha> table{};
  for (int a = 0; a < kAlpha; ++a) {
    const CharlieSheen sheen{kMinSheenAlpha + (1.0f - kMinSheenAlpha) * a / (kAlpha - 1)};
    for (int c = 0; c < kCos; ++c) {
      const float mu = fmax_inline(1e-3f, float(c) / (kCos - 1));
      const vec3 wo(std::sqrt(1.0f - mu * mu), 0.0f, mu);
      double sum = 0.0;
      constexpr int n = 64;
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < 2 * n; ++j) {
          const float z = (i + 0.5f) / n, phi = (j + 0.5f) / (2 * n) * 2.0f * kPi, r = std::sqrt(1.0f - z * z);
          const vec3 wi(r * std::cos(phi), r * std::sin(phi), z);
          sum += sheen.eval(wo, wi) * z;
        }
      table[a * kCos + c] = static_cast<float>(sum * (1.0 / n) * (2.0 * kPi / (2 * n)));
    }
  }
  return table;
}

}  // namespace

float sheen_albedo(float cos_theta, float alpha) {
  static const std::array<float, kCos * kAlpha> table = build_table();
  const float x = glm::clamp(cos_theta, 0.0f, 1.0f) * (kCos - 1);
  const float y = glm::clamp((alpha - kMinSheenAlpha) / (1.0f - kMinSheenAlpha), 0.0f, 1.0f) * (kAlpha - 1);
  const int x0 = std::min(static_cast<int>(x), kCos - 2), y0 = std::min(static_cast<int>(y), kAlpha - 2);
  const float fx = x - x0, fy = y - y0;
  auto at = [&](int i, int j) { return table[j * kCos + i]; };
  return (1 - fx) * (1 - fy) * at(x0, y0) + fx * (1 - fy) * at(x0 + 1, y0) + (1 - fx) * fy * at(x0, y0 + 1) +
         fx * fy * at(x0 + 1, y0 + 1);
}

}  // namespace tessera
