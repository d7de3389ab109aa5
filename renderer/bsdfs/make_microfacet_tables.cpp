// Writes the C++ source of the tables behind microfacet_albedo.h to stdout. Built and run
// at build time (never shipped): each entry integrates the single-scattering lobe over the
// hemisphere with 4096 (1024 for the 3D dielectric tables) visible normals on a lattice;
// the estimator, F G2 / G1, is smooth, so a lattice converges fast and is exact to repeat. The averages integrate the piecewise-linear E(mu) exactly, so they agree with
// the interpolated E the renderer reads (the conductor's compensation needs that).
#include <cmath>
#include <cstdio>
#include <functional>
#include <thread>
#include <vector>

#include "renderer/bsdfs/microfacet.h"
#include "renderer/bsdfs/microfacet_albedo.h"

namespace tessera {
namespace {

constexpr int kInterfacePoints = 1024;

float grid_mu(int i) { return std::fmax(1e-4f, static_cast<float>(i) / (kAlbedoMu - 1)); }
float grid_alpha(int j) {
  const float r = static_cast<float>(j) / (kAlbedoRoughness - 1);
  return std::fmax(kMinAlpha, r * r);
}
float grid_ior(int k) { return 1.0f + (kAlbedoIorMax - 1.0f) * k / (kAlbedoIor - 1); }

vec3 outgoing(float mu) { return {std::sqrt(std::fmax(0.0f, 1.0f - mu * mu)), 0.0f, mu}; }

// Calls f on the visible normals of n points of a Fibonacci lattice ((i + 1/2)/n, frac((i +
// 1/2)/phi)): 1024 of them agree with 16384 to 1e-4 on the interface's albedo, where a
// square grid of 48x48, aliasing with the ring of total internal reflection, is off by 0.7%.
template <typename F>
void over_visible_normals(const GgxDistribution& ggx, const vec3& wo, int n, F&& f) {
  constexpr double kInverseGolden = 0.6180339887498949;
  for (int i = 0; i < n; ++i) {
    const double x = (i + 0.5) / n, y = std::fmod((i + 0.5) * kInverseGolden, 1.0);
    f(ggx.sample_visible(wo, {static_cast<float>(x), static_cast<float>(y)}));
  }
}

// The cosine-weighted average of the piecewise-linear g over the mu grid.
double average(const std::function<double(int)>& g) {
  double sum = 0.0;
  for (int i = 0; i + 1 < kAlbedoMu; ++i) {
    const double m0 = static_cast<double>(i) / (kAlbedoMu - 1), m1 = static_cast<double>(i + 1) / (kAlbedoMu - 1);
    const double g0 = g(i), g1 = g(i + 1), h = m1 - m0;
    // integral over [m0, m1] of (g0 + (g1 - g0)(m - m0)/h) m dm
    sum += g0 * (m1 * m1 - m0 * m0) / 2 + (g1 - g0) / h * (std::pow(m1, 3) / 3 - m0 * m1 * m1 / 2 + std::pow(m0, 3) / 6);
  }
  return 2.0 * sum;
}

void print(const char* name, const std::vector<float>& v) {
  std::printf("const float %s[%zu] = {", name, v.size());
  for (std::size_t i = 0; i < v.size(); ++i) std::printf("%s%.7g", i % 8 ? ", " : ",\n    " + (i == 0), v[i]);
  std::printf("};\n\n");
}

}  // namespace
}  // namespace tessera

int main() {
  using namespace tessera;
  std::vector<float> e(kAlbedoMu * kAlbedoRoughness), e5(e.size());
  for (int j = 0; j < kAlbedoRoughness; ++j) {
    const GgxDistribution ggx{grid_alpha(j)};
    for (int i = 0; i < kAlbedoMu; ++i) {
      const vec3 wo = outgoing(grid_mu(i));
      double sum = 0.0, sum5 = 0.0;
      over_visible_normals(ggx, wo, 4096, [&](const vec3& m) {
        const vec3 wi = reflect(wo, m);
        if (wi.z <= 0.0f) return;
        const double g = ggx.G2(wo, wi) / ggx.G1(wo), c = 1.0 - glm::clamp(glm::dot(wo, m), 0.0f, 1.0f);
        sum += g;
        sum5 += g * (c * c) * (c * c) * c;
      });
      e[j * kAlbedoMu + i] = static_cast<float>(sum / 4096);
      e5[j * kAlbedoMu + i] = static_cast<float>(sum5 / 4096);
    }
  }
  std::vector<float> share(e.size());  // E5 / E: what the BSDF reads per direction
  for (std::size_t k = 0; k < e.size(); ++k) share[k] = e[k] > 0.0f ? e5[k] / e[k] : 0.0f;
  std::vector<float> e_avg(kAlbedoRoughness), share_avg(kAlbedoRoughness);
  for (int j = 0; j < kAlbedoRoughness; ++j) {
    e_avg[j] = static_cast<float>(average([&](int i) { return e[j * kAlbedoMu + i]; }));
    share_avg[j] = static_cast<float>(average([&](int i) { return share[j * kAlbedoMu + i]; }));
  }
  // [side][ior][roughness][mu]: side 0 enters the denser medium (eta = ior), 1 leaves it;
  // one thread per side.
  const std::size_t n3 = 2 * kAlbedoIor * kInterfaceRoughness * kAlbedoMu;
  std::vector<float> reflect_t(n3), transmit_t(n3), reflectance_avg(2 * kAlbedoIor * kInterfaceRoughness);
  auto tabulate_side = [&](int side) {
    for (int k = 0; k < kAlbedoIor; ++k) {
      const float eta = side == 0 ? grid_ior(k) : 1.0f / grid_ior(k);
      for (int j = 0; j < kInterfaceRoughness; ++j) {
        const float r_j = static_cast<float>(j) / (kInterfaceRoughness - 1);
        const GgxDistribution ggx{std::fmax(kMinAlpha, r_j * r_j)};
        const std::size_t row = (static_cast<std::size_t>(side * kAlbedoIor + k) * kInterfaceRoughness + j) * kAlbedoMu;
        for (int i = 0; i < kAlbedoMu; ++i) {
          const vec3 wo = outgoing(grid_mu(i));
          double r = 0.0, t = 0.0;
          over_visible_normals(ggx, wo, kInterfacePoints, [&](const vec3& m) {
            const float f = fresnel_dielectric(glm::dot(wo, m), eta);
            const vec3 wr = reflect(wo, m);
            if (wr.z > 0.0f) r += f * ggx.G2(wo, wr) / ggx.G1(wo);
            vec3 wt;
            if (f < 1.0f && refract(wo, m, eta, wt) && wt.z < 0.0f) t += (1.0f - f) * ggx.G2(wo, wt) / ggx.G1(wo);
          });
          reflect_t[row + i] = static_cast<float>(r / kInterfacePoints);
          transmit_t[row + i] = static_cast<float>(t / kInterfacePoints);
        }
        reflectance_avg[row / kAlbedoMu] = static_cast<float>(average([&](int i) {
          const double sum = reflect_t[row + i] + transmit_t[row + i];
          return sum > 0.0 ? reflect_t[row + i] / sum : 1.0;
        }));
      }
    }
  };
  // [roughness][strength][azimuth][mu]: KHR_materials_anisotropy's lobe; one thread per half.
  std::vector<float> aniso(static_cast<std::size_t>(kAnisoRoughness) * kAnisoStrength * kAnisoAzimuth * kAnisoMu);
  std::vector<float> aniso_share(aniso.size());  // E5 / E
  auto tabulate_anisotropic = [&](int first, int last) {
    for (int j = first; j < last; ++j) {
      const float r = static_cast<float>(j) / (kAnisoRoughness - 1), alpha = std::fmax(kMinAlpha, r * r);
      for (int k = 0; k < kAnisoStrength; ++k) {
        const float strength = static_cast<float>(k) / (kAnisoStrength - 1);
        const GgxDistribution ggx(alpha + (1.0f - alpha) * strength * strength, alpha, {1.0f, 0.0f});
        for (int a = 0; a < kAnisoAzimuth; ++a) {
          const float phi = 0.5f * kPi * a / (kAnisoAzimuth - 1);
          for (int i = 0; i < kAnisoMu; ++i) {
            const float mu = std::fmax(1e-4f, static_cast<float>(i) / (kAnisoMu - 1)), s = std::sqrt(1.0f - mu * mu);
            const vec3 wo(s * std::cos(phi), s * std::sin(phi), mu);
            double sum = 0.0, sum5 = 0.0;
            over_visible_normals(ggx, wo, kInterfacePoints, [&](const vec3& m) {
              const vec3 wi = reflect(wo, m);
              if (wi.z <= 0.0f) return;
              const double g = ggx.G2(wo, wi) / ggx.G1(wo), c = 1.0 - glm::clamp(glm::dot(wo, m), 0.0f, 1.0f);
              sum += g;
              sum5 += g * (c * c) * (c * c) * c;
            });
            const std::size_t at = ((static_cast<std::size_t>(j) * kAnisoStrength + k) * kAnisoAzimuth + a) * kAnisoMu + i;
            aniso[at] = static_cast<float>(sum / kInterfacePoints);
            aniso_share[at] = sum > 0.0 ? static_cast<float>(sum5 / sum) : 0.0f;
          }
        }
      }
    }
  };
  std::thread leaving([&] { tabulate_side(1); tabulate_anisotropic(kAnisoRoughness / 2, kAnisoRoughness); });
  tabulate_side(0);
  tabulate_anisotropic(0, kAnisoRoughness / 2);
  leaving.join();
  std::printf("// Generated by renderer/bsdfs/make_microfacet_tables.cpp at build time. Do not edit.\n");
  std::printf("namespace tessera::albedo_tables {\n\n");
  print("kE", e);
  print("kE5", e5);
  print("kShare", share);
  print("kEAverage", e_avg);
  print("kShareAverage", share_avg);
  print("kReflect", reflect_t);
  print("kTransmit", transmit_t);
  print("kReflectanceAverage", reflectance_avg);
  print("kAnisotropicE", aniso);
  print("kAnisotropicShare", aniso_share);
  std::printf("}  // namespace tessera::albedo_tables\n");
  return 0;
}
