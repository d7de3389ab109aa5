// Wavelengths for dispersion (spectrum.h): the colour matching functions' known integrals,
// the wavelength sampler against its pdf (chi-square), its weights averaging to white, and
// KHR_materials_dispersion's index through a prism against Snell's law with the Cauchy fit
// the Abbe number implies.
#include <gtest/gtest.h>

#include "renderer/bsdfs/bsdf.h"
#include "renderer/bsdfs/spectrum.h"
#include "renderer/sampling/sampler.h"
#include "tests/chi_square.h"

namespace tessera {
namespace {

// CIE 1931: an equal-energy spectrum has X = Y = Z, and y-bar integrates to 106.857 over
// 360-830 nm at 1 nm steps (the tables' sum).
TEST(Spectrum, ColourMatchingFunctionsIntegrateAsTheTables) {
  glm::dvec3 sum(0.0);
  for (int lambda = 360; lambda <= 830; ++lambda) sum += glm::dvec3(cie_xyz(static_cast<float>(lambda)));
  EXPECT_NEAR(sum.y, 106.857, 0.01 * 106.857);
  EXPECT_NEAR(sum.x / sum.y, 1.0, 0.01);
  EXPECT_NEAR(sum.z / sum.y, 1.0, 0.01);
  const vec3 d65_like = xyz_to_linear_srgb(vec3(0.95047f, 1.0f, 1.08883f));  // D65's white point
  EXPECT_NEAR(d65_like.r, 1.0f, 1e-3f);
  EXPECT_NEAR(d65_like.g, 1.0f, 1e-3f);
  EXPECT_NEAR(d65_like.b, 1.0f, 1e-3f);
}

// The weights w / p average to white: a path that picks a wavelength keeps its colour on
// average. Stratified u, so the mean is the integral up to the 1 nm table's resolution.
TEST(Spectrum, WavelengthWeightsAverageToWhite) {
  constexpr int n = 1 << 16;
  glm::dvec3 sum(0.0);
  for (int i = 0; i < n; ++i) {
    const WavelengthSample s = sample_wavelength((i + 0.5f) / n);
    ASSERT_GE(s.lambda, kLambdaMin);
    ASSERT_LT(s.lambda, kLambdaMax);
    ASSERT_GE(glm::min(s.weight.r, glm::min(s.weight.g, s.weight.b)), 0.0f);
    EXPECT_NEAR(s.weight.r + s.weight.g + s.weight.b, 3.0f, 1e-3f);  // p follows w's sum
    sum += glm::dvec3(s.weight);
  }
  sum /= n;
  EXPECT_NEAR(sum.r, 1.0, 2e-3);
  EXPECT_NEAR(sum.g, 1.0, 2e-3);
  EXPECT_NEAR(sum.b, 1.0, 2e-3);
}

// Pearson's chi-square of sampled wavelengths against wavelength_pdf, 10 nm bins (pooled
// below 5 expected), with independent uniform numbers.
TEST(Spectrum, WavelengthSamplingMatchesItsPdfChiSquare) {
  constexpr int n = 200000, bins = 47;
  std::vector<double> observed(bins, 0.0), expected(bins, 0.0);
  std::uint64_t state = 12345;
  for (int i = 0; i < n; ++i) {
    state = mix64(state + 0x9e3779b97f4a7c15ULL);
    const float u = static_cast<float>(state >> 40) * 0x1.0p-24f;
    observed[std::min(bins - 1, static_cast<int>((sample_wavelength(u).lambda - kLambdaMin) / 10.0f))] += 1.0;
  }
  for (int b = 0; b < bins; ++b)
    for (int k = 0; k < 100; ++k) expected[b] += wavelength_pdf(kLambdaMin + 10.0f * b + (k + 0.5f) * 0.1f) * 0.1 * n;
  double chi2 = 0.0, pooled_o = 0.0, pooled_e = 0.0;
  int dof = -1;
  for (int b = 0; b < bins; ++b) {
    if (expected[b] < 5.0) {
      pooled_o += observed[b];
      pooled_e += expected[b];
      continue;
    }
    chi2 += sqr(float(observed[b] - expected[b])) / expected[b];
    ++dof;
  }
  if (pooled_e > 0.0) {
    chi2 += (pooled_o - pooled_e) * (pooled_o - pooled_e) / pooled_e;
    ++dof;
  }
  EXPECT_GT(test::gamma_q(0.5 * dof, 0.5 * chi2), 1e-3) << "chi2 " << chi2 << " dof " << dof;
}

// The Abbe number is what the extension defines: (n_d - 1) / (n_F - n_C) with the Fraunhofer
// lines d, F and C, and n_d the material's index.
TEST(Dispersion, IndexFollowsTheAbbeNumber) {
  for (float ior : {1.5f, 1.8f, 2.4f})
    for (float dispersion : {0.33f, 1.0f, 2.0f}) {
      const float abbe = 20.0f / dispersion;
      const float nd = dispersive_ior(ior, dispersion, 587.6f);
      const float nf = dispersive_ior(ior, dispersion, 486.1f), nc = dispersive_ior(ior, dispersion, 656.3f);
      EXPECT_NEAR(nd, ior, 2e-4f);
      EXPECT_NEAR((nd - 1.0f) / (nf - nc), abbe, 0.002f * abbe);
    }
  EXPECT_EQ(dispersive_ior(1.5f, 0.0f, 400.0f), 1.5f);
}

// Deviation of a ray through a prism of apex angle A entering at incidence theta1, with
// index n: refract at the first face, meet the second at A - theta2, leave at theta4.
double prism_exit_angle(double n, double apex, double theta1) {
  const double theta2 = std::asin(std::sin(theta1) / n);
  return std::asin(n * std::sin(apex - theta2));
}

// Snell and the two-term Cauchy fit n = a + b / lambda^2 through n_d with the Abbe number's
// n_F - n_C, derived here from the Fraunhofer wavelengths, not from the renderer's formula.
double cauchy_index(double nd, double abbe, double lambda) {
  const double b = (nd - 1.0) / (abbe * (1.0 / (486.1 * 486.1) - 1.0 / (656.3 * 656.3)));
  const double a = nd - b / (587.6 * 587.6);
  return a + b / (lambda * lambda);
}

// One refraction by the BSDF of smooth dispersive glass at `lambda` (what the path tracer
// builds): the direction leaving, in the local frame of the face.
vec3 refract_through(const vec3& wo, float eta, const ShadingPoint& glass) {
  const GltfBsdf bsdf(glass, wo, eta);
  BsdfSample s;
  const float u_transmit = 1.0f - 0.5f * bsdf.lobe_probability(GltfBsdf::kTransmission);
  EXPECT_TRUE(bsdf.sample(wo, u_transmit, {0.5f, 0.5f}, s));
  EXPECT_TRUE(s.transmitted);
  return s.wi;
}

// A 60 degree prism of dispersion 1 (Abbe 20) and index 1.6, a ray entering at 50 degrees:
// the exit angle per wavelength from the BSDF's two refractions against Snell with Cauchy.
TEST(Dispersion, PrismExitAnglePerWavelengthMatchesSnell) {
  const double apex = glm::radians(60.0), theta1 = glm::radians(50.0);
  ShadingPoint glass;
  glass.base_color = vec3(1.0f);
  glass.metallic = 0.0f;
  glass.roughness = 0.0f;
  glass.transmission = 1.0f;
  glass.thin_walled = false;
  glass.dispersion = 1.0f;
  double previous = 0.0;
  for (float lambda : {420.0f, 486.1f, 550.0f, 587.6f, 656.3f, 700.0f}) {
    const float n = dispersive_ior(1.6f, glass.dispersion, lambda);
    glass.ior = n;
    // Face 1 in its own frame (normal +z outward): the ray arrives from outside at theta1 in
    // the x-z plane; wo points back along it.
    const vec3 wo1(std::sin(theta1), 0.0f, std::cos(theta1));
    const vec3 inside = refract_through(wo1, n, glass);  // below face 1: z < 0
    // Face 2's outward normal is face 1's turned by 180 - A degrees about y, toward the side
    // the ray travels (-x): the ray inside meets it at theta3 = A - theta2. The BSDF's frame
    // there has z = -n2 (the inner side, where wo = -inside lies) and leaves with eta = 1 / n.
    const float c = static_cast<float>(std::cos(apex)), s = static_cast<float>(std::sin(apex));
    const vec3 n2(-s, 0.0f, -c), t2(c, 0.0f, -s), b2(0.0f, 1.0f, 0.0f);
    const vec3 wo2(glm::dot(-inside, t2), glm::dot(-inside, b2), glm::dot(-inside, -n2));
    ASSERT_GT(wo2.z, 0.0f) << "the ray must reach face 2 from inside";
    const vec3 out = refract_through(wo2, 1.0f / n, glass);
    const double exit = std::acos(std::min(1.0, static_cast<double>(-out.z)));
    const double expected = prism_exit_angle(cauchy_index(1.6, 20.0, lambda), apex, theta1);
    EXPECT_NEAR(glm::degrees(exit), glm::degrees(expected), 0.05) << lambda << " nm";
    if (previous > 0.0) {
      EXPECT_LT(exit, previous) << "longer waves bend less";
    }
    previous = exit;
  }
}

}  // namespace
}  // namespace tessera
