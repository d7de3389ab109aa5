#include "renderer/bsdfs/thin_film.h"

#include "renderer/bsdfs/microfacet.h"
#include "renderer/bsdfs/spectrum.h"

namespace tessera {
namespace {

float schlick(float f0, float cos_theta) {
  const float m = 1.0f - cos_theta, m2 = m * m;
  return f0 + (1.0f - f0) * m2 * m2 * m;
}

float normal_reflectance(float n_to, float n_from) { return sqr((n_to - n_from) / (n_to + n_from)); }

// The m-th Fourier term of the colour matching functions (Belcour and Barla's Gaussian fits,
// normalised by y-bar's integral) at optical path difference opd (nm) and phase shift, in
// Rec. 709, white balanced (see the header).
vec3 sensitivity(float opd, const vec3& shift) {
  const double phase = 2.0 * kPi * opd * 1.0e-9;
  const double val[3] = {5.4856e-13, 4.4201e-13, 5.2481e-13}, pos[3] = {1.6810e+06, 1.7953e+06, 2.2084e+06},
               var[3] = {4.3278e+09, 9.3046e+09, 6.6121e+09};
  double xyz[3];
  for (int i = 0; i < 3; ++i)
    xyz[i] = val[i] * std::sqrt(2.0 * kPi * var[i]) * std::cos(pos[i] * phase + shift[i]) * std::exp(-phase * phase * var[i]);
  xyz[0] += 9.7470e-14 * std::sqrt(2.0 * kPi * 4.5282e+09) * std::cos(2.2399e+06 * phase + shift[0]) *
            std::exp(-4.5282e+09 * phase * phase);
  static const vec3 white = xyz_to_linear_srgb(vec3(1.0f));
  return xyz_to_linear_srgb(vec3(xyz[0], xyz[1], xyz[2]) / 1.0685e-7f) / white;
}

}  // namespace

vec3 thin_film_reflectance(const ThinFilm& film, float cos_theta, const vec3& base_f0) {
  const float n1 = film.outside_ior, n2 = film.ior, cos1 = glm::clamp(cos_theta, 0.0f, 1.0f);
  const float sin2_sq = sqr(n1 / n2) * (1.0f - cos1 * cos1);
  if (sin2_sq >= 1.0f) return vec3(1.0f);  // total internal reflection at the film's top
  const float cos2 = std::sqrt(1.0f - sin2_sq);
  // Outside to film: reflectance, transmittance there and back, and the phase shift of the
  // reflection inside the film (pi when the film is the rarer medium).
  const float r12 = schlick(normal_reflectance(n2, n1), cos1), t121 = 1.0f - r12;
  const float phi21 = n2 < n1 ? 0.0f : kPi;
  // Film to base, per channel.
  vec3 r23, phi23;
  for (int c = 0; c < 3; ++c) {
    const float s = std::sqrt(glm::clamp(base_f0[c], 0.0f, 0.9999f));
    const float base_ior = (1.0f + s) / (1.0f - s);
    r23[c] = schlick(normal_reflectance(base_ior, n2), cos2);
    phi23[c] = base_ior < n2 ? kPi : 0.0f;
  }
  const float opd = 2.0f * n2 * film.thickness * cos2;
  const vec3 phi = vec3(phi21) + phi23;
  const vec3 r123 = glm::sqrt(glm::clamp(r12 * r23, vec3(1e-5f), vec3(0.9999f)));
  const vec3 rs = t121 * t121 * r23 / (vec3(1.0f) - r123 * r123);
  vec3 reflectance = r12 + rs;  // m = 0: the incoherent sum
  vec3 cm = rs - t121;
  for (int m = 1; m <= 2; ++m) {
    cm *= r123;
    reflectance += cm * 2.0f * sensitivity(m * opd, float(m) * phi);
  }
  return glm::max(reflectance, vec3(0.0f));
}

}  // namespace tessera
