// The glTF BSDF: its sampling routine against its own pdf (chi-square), the microfacet
// distribution's normalisation, reciprocity, and the energy each material reflects.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "renderer/integrator/bsdf.h"
#include "renderer/sampler.h"
#include "tests/chi_square.h"

namespace tessera {
namespace {

vec3 direction(float theta_degrees, float phi_degrees = 30.0f) {
  const float t = glm::radians(theta_degrees), p = glm::radians(phi_degrees);
  return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

struct Config {
  std::string name;
  ShadingPoint sp;
  float eta = 1.5f;
};

ShadingPoint material(float metallic, float roughness, vec3 base = vec3(0.8f, 0.6f, 0.4f)) {
  ShadingPoint sp;
  sp.base_color = base;
  sp.metallic = metallic;
  sp.roughness = roughness;
  return sp;
}

std::vector<Config> configs() {
  std::vector<Config> out;
  for (float r : {0.2f, 0.5f, 1.0f}) {
    out.push_back({"dielectric r" + std::to_string(r), material(0.0f, r)});
    out.push_back({"metal r" + std::to_string(r), material(1.0f, r)});
    out.push_back({"half-metal r" + std::to_string(r), material(0.5f, r)});
    ShadingPoint thin = material(0.0f, r, vec3(0.9f));
    thin.transmission = 1.0f;
    out.push_back({"thin glass r" + std::to_string(r), thin});
    ShadingPoint thick = thin;
    thick.thin_walled = false;
    out.push_back({"glass entering r" + std::to_string(r), thick, 1.5f});
    out.push_back({"glass leaving r" + std::to_string(r), thick, 1.0f / 1.5f});
    ShadingPoint coated = material(0.0f, r);
    coated.clearcoat = 1.0f;
    coated.clearcoat_roughness = 0.3f;
    out.push_back({"clearcoat r" + std::to_string(r), coated});
    ShadingPoint mixed = material(0.3f, r);
    mixed.transmission = 0.5f;
    mixed.specular = 0.5f;
    mixed.specular_color = vec3(1.0f, 0.5f, 0.25f);
    out.push_back({"mixed r" + std::to_string(r), mixed});
    ShadingPoint velvet = material(0.0f, r, vec3(0.2f, 0.1f, 0.1f));
    velvet.sheen_color = vec3(0.9f, 0.4f, 0.6f);
    velvet.sheen_roughness = r;
    out.push_back({"sheen r" + std::to_string(r), velvet});
  }
  return out;
}

// Every configuration at three incident angles. 30 x 3 tests, each at significance
// 0.001 / 90 (Sidak-style correction), so a correct sampler fails with probability 0.1%.
TEST(GltfBsdf, SamplingMatchesItsPdfChiSquare) {
  const std::vector<Config> all = configs();
  const double alpha = 1e-3 / (3.0 * all.size());
  for (const Config& c : all) {
    for (float theta : {10.0f, 45.0f, 80.0f}) {
      const vec3 wo = direction(theta);
      const GltfBsdf bsdf(c.sp, wo, c.eta);
      auto sample = [&](int i) -> std::optional<glm::vec3> {
        Sampler rng(SamplerKind::independent, i, 0, 0, 17);
        BsdfSample s;
        const float u = rng.next();
        if (!bsdf.sample(wo, u, rng.next2(), s)) return std::nullopt;
        return s.wi;
      };
      auto pdf = [&](const glm::vec3& wi) { return bsdf.pdf(wo, wi); };
      const test::ChiSquareResult r = test::chi_square_test(sample, pdf, 200000);
      EXPECT_GT(r.p_value, alpha) << c.name << " theta " << theta << ": chi2 " << r.statistic << " dof " << r.dof;
      // The pdf's integral is the probability that sampling succeeds.
      EXPECT_NEAR(r.pdf_integral, r.sampled_fraction, 0.01) << c.name << " theta " << theta;
    }
  }
}

// What sample() returns is what eval() and pdf() say for that direction.
TEST(GltfBsdf, SampleAgreesWithEvalAndPdf) {
  for (const Config& c : configs()) {
    const vec3 wo = direction(35.0f);
    const GltfBsdf bsdf(c.sp, wo, c.eta);
    for (int i = 0; i < 2000; ++i) {
      Sampler rng(SamplerKind::independent, i, 1, 0, 5);
      BsdfSample s;
      const float u = rng.next();
      if (!bsdf.sample(wo, u, rng.next2(), s)) continue;
      ASSERT_FLOAT_EQ(s.pdf, bsdf.pdf(wo, s.wi)) << c.name;
      ASSERT_EQ(s.f, bsdf.eval(wo, s.wi)) << c.name;
      ASSERT_EQ(s.transmitted, s.wi.z < 0.0f) << c.name;
    }
  }
}

// Quadrature over the hemisphere of m: the NDF projected on the normal and the
// distribution of visible normals both integrate to one.
TEST(Microfacet, DistributionsIntegrateToOne) {
  for (float alpha : {0.05f, 0.2f, 0.6f, 1.0f}) {
    const GgxDistribution d{alpha};
    const vec3 wo = direction(60.0f);
    double ndf = 0.0, vndf = 0.0;
    const int n = 2000;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < 400; ++j) {
        // cos theta spaced densely near 1, where narrow lobes live: cos = 1 - x^4.
        const double x0 = double(i) / n, x1 = double(i + 1) / n;
        const double c0 = 1 - std::pow(x0, 4), c1 = 1 - std::pow(x1, 4);
        const double c = 0.5 * (c0 + c1), phi = (j + 0.5) / 400 * 2 * M_PI;
        const double s = std::sqrt(1 - c * c);
        const vec3 m(s * std::cos(phi), s * std::sin(phi), c);
        const double dw = (c0 - c1) * 2 * M_PI / 400;
        ndf += d.D(m) * m.z * dw;
        vndf += d.visible_pdf(wo, m) * dw;
      }
    EXPECT_NEAR(ndf, 1.0, 2e-3) << "alpha " << alpha;
    EXPECT_NEAR(vndf, 1.0, 2e-3) << "alpha " << alpha;
  }
}

// f(wo, wi) = f(wi, wo) for the reflection lobes (the clear coat's Fresnel weight depends
// on the viewing direction only, as the glTF specification writes it, so it is left out).
TEST(GltfBsdf, ReflectionIsReciprocal) {
  for (const Config& c : configs()) {
    if (c.sp.clearcoat > 0.0f) continue;
    for (int i = 0; i < 200; ++i) {
      Sampler rng(SamplerKind::independent, i, 2, 0, 9);
      const vec3 a = direction(85.0f * rng.next(), 360.0f * rng.next());
      const vec3 b = direction(85.0f * rng.next(), 360.0f * rng.next());
      const vec3 fab = GltfBsdf(c.sp, a, c.eta).eval(a, b), fba = GltfBsdf(c.sp, b, c.eta).eval(b, a);
      for (int k = 0; k < 3; ++k) ASSERT_NEAR(fab[k], fba[k], 1e-4f * std::fmax(1.0f, fab[k])) << c.name;
    }
  }
}

// Directional albedo: the fraction of light from wo that the BSDF scatters, estimated from
// its own samples (f cos / pdf) and, independently, by quadrature of f cos over the sphere.
// Refraction scales radiance by 1/eta^2 (the same flux through a compressed solid angle);
// weighting transmitted directions by eta^2 turns the radiance albedo back into flux.
struct Albedo {
  double sampled, quadrature;
};

Albedo albedo(const ShadingPoint& sp, const vec3& wo, float eta) {
  const GltfBsdf bsdf(sp, wo, eta);
  double sampled = 0.0;
  const int n = 400000;
  for (int i = 0; i < n; ++i) {
    Sampler rng(SamplerKind::independent, i, 3, 0, 11);
    BsdfSample s;
    const float u = rng.next();
    if (bsdf.sample(wo, u, rng.next2(), s))
      sampled += luminance(s.f) * std::fabs(s.wi.z) / s.pdf * (s.transmitted && !sp.thin_walled ? eta * eta : 1.0f);
  }
  double quad = 0.0;
  const int nt = 1500, np = 300;
  for (int i = 0; i < nt; ++i)
    for (int j = 0; j < np; ++j) {
      const double c = -1.0 + (i + 0.5) * 2.0 / nt, phi = (j + 0.5) * 2 * M_PI / np;
      const double s = std::sqrt(1 - c * c);
      const vec3 wi(s * std::cos(phi), s * std::sin(phi), c);
      const double flux = c < 0 && !sp.thin_walled ? eta * eta : 1.0;
      quad += luminance(bsdf.eval(wo, wi)) * std::fabs(c) * flux * (2.0 / nt) * (2 * M_PI / np);
    }
  return {sampled / n, quad};
}

// White furnace per material: white base colour; what comes back never exceeds what came
// in, and is at least the known single-scattering floor. GGX without multiple scattering
// loses energy at high roughness (see the closed form below); smooth lobes keep nearly all.
TEST(GltfBsdf, WhiteFurnaceEnergyPerMaterial) {
  struct Case {
    const char* name;
    ShadingPoint sp;
    float eta;
    double lo, hi;  // bounds on the albedo at 45 degrees
  };
  auto white = [](float metallic, float roughness) { return material(metallic, roughness, vec3(1.0f)); };
  ShadingPoint lambert = white(0.0f, 1.0f);
  lambert.specular = 0.0f;
  ShadingPoint glass = white(0.0f, 0.05f);
  glass.transmission = 1.0f;
  glass.thin_walled = false;
  ShadingPoint thin = glass;
  thin.thin_walled = true;
  ShadingPoint rough_glass = glass;
  rough_glass.roughness = 0.6f;
  ShadingPoint sheened = lambert;
  sheened.sheen_color = vec3(1.0f);
  sheened.sheen_roughness = 0.5f;
  ShadingPoint coated = white(0.0f, 0.5f);
  coated.clearcoat = 1.0f;
  coated.clearcoat_roughness = 0.1f;
  const Case cases[] = {
      {"lambert", lambert, 1.5f, 0.999, 1.001},
      {"metal smooth", white(1.0f, 0.05f), 1.5f, 0.99, 1.001},
      {"metal r0.5", white(1.0f, 0.5f), 1.5f, 0.85, 0.95},
      {"metal r1", white(1.0f, 1.0f), 1.5f, 0.35, 0.40},
      {"dielectric r0.5", white(0.0f, 0.5f), 1.5f, 0.90, 1.02},
      {"thick glass smooth", glass, 1.5f, 0.99, 1.001},
      {"thick glass leaving", glass, 1.0f / 1.5f, 0.99, 1.001},
      {"thick glass rough", rough_glass, 1.5f, 0.85, 1.001},
      {"thin glass smooth", thin, 1.5f, 0.99, 1.001},
      {"clearcoat", coated, 1.5f, 0.90, 1.02},
      {"sheen", sheened, 1.5f, 0.90, 1.001},
  };
  for (const Case& c : cases) {
    const Albedo a = albedo(c.sp, direction(45.0f), c.eta);
    // The quadrature resolves lobes down to roughness 0.3; narrower ones rely on sampling.
    if (c.sp.roughness >= 0.3f) {
      EXPECT_NEAR(a.sampled, a.quadrature, 0.01) << c.name;
    }
    EXPECT_GE(a.sampled, c.lo) << c.name;
    EXPECT_LE(a.sampled, c.hi) << c.name;
  }
}

// The tabulated sheen albedo against direct quadrature of the Charlie BRDF.
TEST(Sheen, AlbedoTableMatchesQuadrature) {
  for (float alpha : {0.1f, 0.3f, 0.8f})
    for (float mu : {0.2f, 0.5f, 0.9f}) {
      const CharlieSheen sheen{alpha};
      const vec3 wo(std::sqrt(1 - mu * mu), 0.0f, mu);
      double sum = 0.0;
      const int n = 400;
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < 2 * n; ++j) {
          const double z = (i + 0.5) / n, phi = (j + 0.5) / (2 * n) * 2 * M_PI, r = std::sqrt(1 - z * z);
          sum += sheen.eval(wo, vec3(r * std::cos(phi), r * std::sin(phi), z)) * z;
        }
      const double e = sum * (1.0 / n) * (M_PI / n);
      EXPECT_NEAR(sheen_albedo(mu, alpha), e, 0.01 * e + 1e-3) << "alpha " << alpha << " mu " << mu;
      EXPECT_LE(e, 1.0);
    }
}

// A white metal at roughness 1 (alpha 1): D = 1/pi and Lambda(w) = (1/cos - 1)/2, so the
// albedo integral has a closed form: E(mu) = 1 - mu ln((1 + mu) / mu). It measures the
// single-scattering energy loss of this GGX exactly (62% at 45 degrees).
TEST(GltfBsdf, RoughMetalAlbedoMatchesTheClosedForm) {
  ShadingPoint metal = material(1.0f, 1.0f, vec3(1.0f));
  for (float theta : {0.0f, 30.0f, 45.0f, 70.0f}) {
    const double mu = std::cos(glm::radians(theta));
    const Albedo a = albedo(metal, direction(theta), 1.5f);
    const double expected = 1.0 - mu * std::log((1.0 + mu) / mu);
    EXPECT_NEAR(a.sampled, expected, 0.005) << "theta " << theta;
    EXPECT_NEAR(a.quadrature, expected, 0.002) << "theta " << theta;
  }
}

}  // namespace
}  // namespace tessera
