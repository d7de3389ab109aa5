// KHR_materials_iridescence's thin film against the exact Airy reflectance of a film
// integrated over the spectrum with the colour matching functions (a second method: the
// film's code sums the same series in Fourier space with other fits of the functions).
#include <gtest/gtest.h>

#include <complex>
#include <string>

#include "renderer/bsdfs/bsdf.h"
#include "renderer/bsdfs/spectrum.h"
#include "renderer/bsdfs/thin_film.h"

namespace tessera {
namespace {

// Airy: the reflectance at normal incidence of a film of index n2 and thickness d (nm) between
// n1 and n3, at wavelength lambda: |r12 + r23 e^(i delta)|^2 / |1 + r12 r23 e^(i delta)|^2,
// delta = 4 pi n2 d / lambda (the round trip's phase).
double airy(double n1, double n2, double n3, double d, double lambda) {
  const double r12 = (n1 - n2) / (n1 + n2), r23 = (n2 - n3) / (n2 + n3);
  const std::complex<double> e = std::polar(1.0, 4.0 * M_PI * n2 * d / lambda);
  return std::norm((r12 + r23 * e) / (1.0 + r12 * r23 * e));
}

// Its Rec. 709 colour: each channel's sensitivity (the colour matching functions through the
// XYZ to RGB matrix) weighting the reflectance, normalised so a flat spectrum keeps its
// value; negative results (outside the gamut) clipped as the film's code clips.
vec3 airy_rgb(double n2, double n3, double d) {
  glm::dvec3 sum(0.0), norm(0.0);
  for (double lambda = 360.0; lambda < 830.0; lambda += 0.25) {
    const glm::dvec3 s(xyz_to_linear_srgb(cie_xyz(static_cast<float>(lambda))));
    sum += s * airy(1.0, n2, n3, d, lambda);
    norm += s;
  }
  return glm::max(vec3(sum / norm), vec3(0.0f));
}

vec3 f0_of(float ior) { return vec3(sqr((ior - 1.0f) / (ior + 1.0f))); }

TEST(ThinFilm, NormalIncidenceMatchesAirySummation) {
  double worst = 0.0, total = 0.0;
  int count = 0;
  for (float n2 : {1.2f, 1.3f, 1.5f, 1.8f, 2.0f})
    for (float n3 : {1.0f, 1.33f, 1.5f, 2.0f, 3.0f})
      for (float d : {100.0f, 200.0f, 300.0f, 400.0f, 600.0f, 800.0f, 1200.0f}) {
        const vec3 expected = airy_rgb(n2, n3, d);
        const vec3 got = thin_film_reflectance(ThinFilm{d, n2, 1.0f}, 1.0f, f0_of(n3));
        const float error = max_component(glm::abs(got - expected));
        worst = std::max<double>(worst, error);
        total += error;
        ++count;
        // Measured: at most 0.026 (a 2.0 film on 1.0 at 800 nm), 0.005 on average; the
        // extension's own formula, without the white balance, 0.042 and 0.011.
        EXPECT_LE(error, 0.03) << "film " << n2 << " on " << n3 << ", " << d << " nm: got " << got.r << " "
                               << got.g << " " << got.b << ", Airy " << expected.r << " " << expected.g << " "
                               << expected.b;
      }
  EXPECT_LE(total / count, 0.006) << "worst " << worst;
}

// A quarter-wave coating (n2 = sqrt(n3), n2 d = 550 / 4) cancels green's reflection: the
// film turns the bare base's 6.6% into almost nothing, and leaves red and blue brighter.
TEST(ThinFilm, QuarterWaveCoatingCancelsGreen) {
  const float n3 = 1.69f, n2 = 1.3f, d = 550.0f / (4.0f * n2);
  const vec3 bare = f0_of(n3);
  const vec3 coated = thin_film_reflectance(ThinFilm{d, n2, 1.0f}, 1.0f, bare);
  EXPECT_LT(coated.g, 0.1f * bare.g);
  EXPECT_GT(coated.r, coated.g);
  EXPECT_GT(coated.b, coated.g);
}

// At grazing incidence everything is reflected, as for any interface.
TEST(ThinFilm, GrazingReflectsEverything) {
  const vec3 r = thin_film_reflectance(ThinFilm{400.0f, 1.3f, 1.0f}, 0.0f, f0_of(1.5f));
  EXPECT_NEAR(r.r, 1.0f, 1e-5f);
  EXPECT_NEAR(r.g, 1.0f, 1e-5f);
  EXPECT_NEAR(r.b, 1.0f, 1e-5f);
}

// The BSDF uses the film: a smooth iridescent dielectric reflects, at normal incidence, the
// film's reflectance (the specular lobe's mirror direction, integrated over its narrow lobe).
TEST(ThinFilm, SmoothIridescentDielectricReflectsTheFilm) {
  ShadingPoint sp;
  sp.base_color = vec3(0.0f);  // only the specular layer
  sp.metallic = 0.0f;
  sp.roughness = 0.0f;
  sp.iridescence = 1.0f;
  sp.iridescence_ior = 1.3f;
  sp.iridescence_thickness = 300.0f;
  const vec3 wo(0.0f, 0.0f, 1.0f);
  const GltfBsdf bsdf(sp, wo, 1.5f);
  BsdfSample s;
  ASSERT_TRUE(bsdf.sample(wo, 0.5f, {0.3f, 0.7f}, s));
  const vec3 weight = s.f * std::fabs(s.wi.z) / s.pdf;  // estimate of the reflected share
  const vec3 film = thin_film_reflectance(ThinFilm{300.0f, 1.3f, 1.0f}, 1.0f, f0_of(1.5f));
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(weight[c], film[c], 0.002f) << "channel " << c;
}

}  // namespace
}  // namespace tessera
