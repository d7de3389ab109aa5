#include "renderer/bsdfs/spectrum.h"

#include <algorithm>
#include <array>

namespace tessera {
namespace {

// A Gaussian with different widths below and above its peak.
float lobe(float lambda, float peak, float below, float above) {
  const float t = (lambda - peak) / (lambda < peak ? below : above);
  return std::exp(-0.5f * t * t);
}

constexpr int kBins = static_cast<int>(kLambdaMax - kLambdaMin);  // 1 nm each

// w per bin and the cumulative distribution of p, built once.
struct ResponseTable {
  std::array<vec3, kBins> response;
  std::array<float, kBins + 1> cdf;

  ResponseTable() {
    vec3 integral(0.0f);
    for (int i = 0; i < kBins; ++i) {
      response[i] = glm::max(xyz_to_linear_srgb(cie_xyz(kLambdaMin + i + 0.5f)), vec3(0.0f));
      integral += response[i];
    }
    cdf[0] = 0.0f;
    for (int i = 0; i < kBins; ++i) {
      response[i] /= integral;
      cdf[i + 1] = cdf[i] + (response[i].r + response[i].g + response[i].b) / 3.0f;
    }
  }
};

const ResponseTable& table() {
  static const ResponseTable t;
  return t;
}

int bin_of(float lambda) { return std::clamp(static_cast<int>(lambda - kLambdaMin), 0, kBins - 1); }

}  // namespace

vec3 cie_xyz(float lambda) {
  return {1.056f * lobe(lambda, 599.8f, 37.9f, 31.0f) + 0.362f * lobe(lambda, 442.0f, 16.0f, 26.7f) -
              0.065f * lobe(lambda, 501.1f, 20.4f, 26.2f),
          0.821f * lobe(lambda, 568.8f, 46.9f, 40.5f) + 0.286f * lobe(lambda, 530.9f, 16.3f, 31.1f),
          1.217f * lobe(lambda, 437.0f, 11.8f, 36.0f) + 0.681f * lobe(lambda, 459.0f, 26.0f, 13.8f)};
}

vec3 xyz_to_linear_srgb(const vec3& c) {
  return {3.2404542f * c.x - 1.5371385f * c.y - 0.4985314f * c.z,
          -0.9692660f * c.x + 1.8760108f * c.y + 0.0415560f * c.z,
          0.0556434f * c.x - 0.2040259f * c.y + 1.0572252f * c.z};
}

vec3 wavelength_response(float lambda) {
  if (!(lambda >= kLambdaMin && lambda < kLambdaMax)) return vec3(0.0f);
  return table().response[bin_of(lambda)];
}

float wavelength_pdf(float lambda) {
  const vec3 w = wavelength_response(lambda);
  return (w.r + w.g + w.b) / (3.0f * table().cdf[kBins]);
}

WavelengthSample sample_wavelength(float u) {
  const ResponseTable& t = table();
  const float target = u * t.cdf[kBins];
  const int i = std::clamp(static_cast<int>(std::upper_bound(t.cdf.begin(), t.cdf.end(), target) - t.cdf.begin()) - 1,
                           0, kBins - 1);
  const float mass = t.cdf[i + 1] - t.cdf[i];  // for the position in the bin only: rounding
  const float frac = mass > 0.0f ? std::clamp((target - t.cdf[i]) / mass, 0.0f, 0.99999f) : 0.5f;
  WavelengthSample s;
  s.lambda = fmin_inline(kLambdaMin + i + frac, kLambdaMax - 1e-3f);
  // p from the bin itself: exact where the cdf's differences are tiny (and s.lambda may
  // round into the next bin).
  const vec3& w = t.response[i];
  const float pdf = (w.r + w.g + w.b) / (3.0f * t.cdf[kBins]);
  s.weight = pdf > 0.0f ? w / pdf : vec3(0.0f);
  return s;
}

}  // namespace tessera
