#include "renderer/bsdfs/microfacet_albedo.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "renderer/util/math.h"
#include "renderer/bsdfs/microfacet_tables.inc"  // generated: the build directory

namespace tessera {
namespace {

using namespace albedo_tables;

// Position of x in [0, 1] on a grid of n points: the lower index and the weight of the upper.
struct GridPos {
  int i;
  float t;
};
GridPos locate(float x, int n) {
  const float s = std::clamp(x, 0.0f, 1.0f) * static_cast<float>(n - 1);
  const int i = std::min(static_cast<int>(s), n - 2);
  return {i, s - static_cast<float>(i)};
}

float lerp(float a, float b, float t) { return a + t * (b - a); }

// Bilinear in (mu, roughness) within one [roughness][mu] plane.
float plane(const float* table, float mu, float roughness, int roughness_points = kAlbedoRoughness) {
  const GridPos m = locate(mu, kAlbedoMu), r = locate(roughness, roughness_points);
  const float* row0 = table + static_cast<std::ptrdiff_t>(r.i) * kAlbedoMu;
  const float* row1 = row0 + kAlbedoMu;
  return lerp(lerp(row0[m.i], row0[m.i + 1], m.t), lerp(row1[m.i], row1[m.i + 1], m.t), r.t);
}

float row(const float* table, float roughness, int roughness_points = kAlbedoRoughness) {
  const GridPos r = locate(roughness, roughness_points);
  return lerp(table[r.i], table[r.i + 1], r.t);
}

// The side of the interface (0: into the denser medium) and the position on the ior grid.
struct IorPos {
  int side;
  GridPos at;
};
IorPos locate_ior(float eta) {
  const int side = eta >= 1.0f ? 0 : 1;
  const float ior = side == 0 ? eta : 1.0f / eta;
  return {side, locate((ior - 1.0f) / (kAlbedoIorMax - 1.0f), kAlbedoIor)};
}

template <typename Read>
float across_ior(float eta, Read read) {
  const IorPos p = locate_ior(eta);
  const int k = p.side * kAlbedoIor + p.at.i;
  return lerp(read(k), read(k + 1), p.at.t);
}

// Per roughness row: the cumulative share of integral (1 - E) mu dmu up to each grid point.
struct MultiScatterRows {
  float cdf[kAlbedoRoughness][kAlbedoMu];
  MultiScatterRows() {
    for (int j = 0; j < kAlbedoRoughness; ++j) {
      const float* e = kE + j * kAlbedoMu;
      double acc = 0.0;
      cdf[j][0] = 0.0f;
      std::vector<double> sums(kAlbedoMu, 0.0);
      for (int i = 0; i + 1 < kAlbedoMu; ++i) {
        const double m0 = double(i) / (kAlbedoMu - 1), m1 = double(i + 1) / (kAlbedoMu - 1);
        // Trapezoid of the product: plenty for a sampling density (any positive shape is exact).
        acc += 0.5 * ((1.0 - e[i]) * m0 + (1.0 - e[i + 1]) * m1) * (m1 - m0) + 1e-12;
        sums[i + 1] = acc;
      }
      for (int i = 0; i < kAlbedoMu; ++i) cdf[j][i] = static_cast<float>(sums[i] / acc);
      cdf[j][kAlbedoMu - 1] = 1.0f;
    }
  }
};

const MultiScatterRows& multiscatter_rows() {
  static const MultiScatterRows rows;
  return rows;
}

// The nearest grid row, as std::lround would round (halves up), without a library call.
int nearest_row(float roughness) {
  const float s = std::clamp(roughness, 0.0f, 1.0f) * static_cast<float>(kAlbedoRoughness - 1);
  const int i = static_cast<int>(s);
  return s - static_cast<float>(i) >= 0.5f ? i + 1 : i;
}

}  // namespace

MultiScatterShape::MultiScatterShape(float roughness) : cdf_(multiscatter_rows().cdf[nearest_row(roughness)]) {}

float MultiScatterShape::sample_mu(float u) const {
  int i = 0;
  while (i + 2 < kAlbedoMu && cdf_[i + 1] <= u) ++i;
  const float share = cdf_[i + 1] - cdf_[i];
  const float t = share > 0.0f ? std::clamp((u - cdf_[i]) / share, 0.0f, 1.0f) : 0.5f;
  return (static_cast<float>(i) + t) / (kAlbedoMu - 1);
}

void AlbedoSlice::set_roughness(float roughness) {
  const GridPos r = locate(roughness, kAlbedoRoughness);
  e0_ = kE + r.i * kAlbedoMu;
  e1_ = e0_ + kAlbedoMu;
  s0_ = kShare + r.i * kAlbedoMu;
  s1_ = s0_ + kAlbedoMu;
  t_ = r.t;
  albedo_average = lerp(kEAverage[r.i], kEAverage[r.i + 1], r.t);
  share_average = lerp(kShareAverage[r.i], kShareAverage[r.i + 1], r.t);
}

AnisotropicAlbedo anisotropic_ggx_albedo(float mu, float azimuth, float roughness, float strength) {
  const GridPos m = locate(mu, kAnisoMu), a = locate(azimuth / (0.5f * kPi), kAnisoAzimuth);
  const GridPos r = locate(roughness, kAnisoRoughness), s = locate(strength, kAnisoStrength);
  // [roughness][strength][azimuth][mu], linear in each.
  auto read = [&](const float* table) {
    auto at = [&](int ri, int si, int ai) {
      const float* v = table + ((static_cast<std::ptrdiff_t>(ri) * kAnisoStrength + si) * kAnisoAzimuth + ai) * kAnisoMu;
      return lerp(v[m.i], v[m.i + 1], m.t);
    };
    auto over_azimuth = [&](int ri, int si) { return lerp(at(ri, si, a.i), at(ri, si, a.i + 1), a.t); };
    auto over_strength = [&](int ri) { return lerp(over_azimuth(ri, s.i), over_azimuth(ri, s.i + 1), s.t); };
    return lerp(over_strength(r.i), over_strength(r.i + 1), r.t);
  };
  return {read(kAnisotropicE), read(kAnisotropicShare)};
}

float ggx_albedo(float mu, float roughness) { return plane(kE, mu, roughness); }
float ggx_schlick_albedo(float mu, float roughness) { return plane(kE5, mu, roughness); }
float ggx_albedo_average(float roughness) { return row(kEAverage, roughness); }
float ggx_schlick_share_average(float roughness) { return row(kShareAverage, roughness); }

InterfaceAlbedo dielectric_albedo(float mu, float roughness, float eta) {
  const std::ptrdiff_t plane_size = kInterfaceRoughness * kAlbedoMu;
  return {across_ior(eta, [&](int k) { return plane(kReflect + k * plane_size, mu, roughness, kInterfaceRoughness); }),
          across_ior(eta, [&](int k) { return plane(kTransmit + k * plane_size, mu, roughness, kInterfaceRoughness); })};
}

float dielectric_reflectance_average(float roughness, float eta) {
  return across_ior(eta, [&](int k) {
    return row(kReflectanceAverage + k * kInterfaceRoughness, roughness, kInterfaceRoughness);
  });
}

}  // namespace tessera
