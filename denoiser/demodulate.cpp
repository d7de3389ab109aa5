#include "denoiser/demodulate.h"

#include <algorithm>
#include <cmath>

namespace tessera::denoiser {

Planes demodulation_factor(const DenoiseInput& in, float epsilon) {
  return demodulation_factor(to_planes(in.albedo, in.width, in.height, 3), epsilon);
}

Planes demodulation_factor(const Planes& features, float epsilon) {
  Planes f(features.width, features.height, 3);
  for (std::size_t i = 0; i < f.pixels(); ++i)
    for (int k = 0; k < 3; ++k) {
      const float a = features.at(k, i);
      f.at(k, i) = (std::isfinite(a) ? std::max(a, 0.0f) : 0.0f) + epsilon;
    }
  return f;
}

DenoiseInput demodulated_colour(const DenoiseInput& in, const Planes& factor) {
  DenoiseInput out;
  out.width = in.width, out.height = in.height;
  out.samples = in.samples;
  const std::size_t n = factor.pixels();
  for (auto [src, dst] : {std::pair{&in.color_even, &out.color_even}, std::pair{&in.color_odd, &out.color_odd}}) {
    dst->resize(src->size());
    for (std::size_t i = 0; i < n; ++i)
      for (int k = 0; k < 3; ++k) (*dst)[3 * i + k] = (*src)[3 * i + k] / factor.at(k, i);  // NaN stays NaN: missing
  }
  if (!in.variance.empty()) {  // of the colour divided by a constant: divided by its square
    out.variance.resize(in.variance.size());
    for (std::size_t i = 0; i < n; ++i)
      for (int k = 0; k < 3; ++k) out.variance[3 * i + k] = in.variance[3 * i + k] / (factor.at(k, i) * factor.at(k, i));
  }
  return out;
}

void remodulate(Planes& colour, const Planes& factor) {
  for (std::size_t j = 0; j < colour.data.size(); ++j) colour.data[j] *= factor.data[j];
}

void remodulate(Halves& halves, const Planes& factor) {
  Planes square = factor;
  for (float& v : square.data) v *= v;
  for (Half& h : halves.h) {
    remodulate(h.color, factor);
    remodulate(h.variance, square);
    remodulate(h.pixel_variance, square);
  }
}

}  // namespace tessera::denoiser
