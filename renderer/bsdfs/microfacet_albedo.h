// Directional albedos of the single-scattering GGX lobes, tabulated by
// make_microfacet_tables.cpp at build time, for energy compensation: what a rough
// microfacet surface loses to its single-scattering model is the light that scatters more
// than once among the microfacets, and these albedos say how much that is.
//   E(mu, r):       the lobe with Fresnel 1, the conductor's and the thin interface's loss
//   E5(mu, r):      the lobe weighted by Schlick's (1 - wo.h)^5, so that with Schlick's
//                   Fresnel of any f0 the reflectance is f0 E + (1 - f0) E5
//   dielectric:     reflection and refraction of an exact-Fresnel interface of relative index
//                   eta (entering a denser medium, eta > 1, or leaving it, eta < 1)
//   anisotropic:    E of KHR_materials_anisotropy's lobe (alpha r^2 across the direction,
//                   mix(r^2, 1, strength^2) along it) per strength and wo's azimuth to the
//                   direction (symmetric: 0 to 90 degrees)
// mu is the cosine of the outgoing direction, r the glTF roughness (alpha = r^2). Averages
// are cosine-weighted over the hemisphere: avg(g) = 2 * integral of g(mu) mu dmu.
#pragma once

namespace tessera {

// The tables' grid: mu and roughness in [0, 1], the index of refraction of the denser side
// in [1, 3]; each interpolated linearly between grid points. The interface's tables vary
// fast with the index near the critical angle and slowly with roughness.
constexpr int kAlbedoMu = 32, kAlbedoRoughness = 32, kInterfaceRoughness = 16, kAlbedoIor = 32;
constexpr float kAlbedoIorMax = 3.0f;
constexpr int kAnisoMu = 32, kAnisoRoughness = 16, kAnisoStrength = 8, kAnisoAzimuth = 8;

float ggx_albedo(float mu, float roughness);  // E
float ggx_schlick_albedo(float mu, float roughness);  // E5
float ggx_albedo_average(float roughness);  // avg(E)
float ggx_schlick_share_average(float roughness);  // avg(E5 / E)

// The isotropic tables at one roughness: the lookups of one shading point share the
// roughness interpolation, and read E5 / E from its own table (no division per lookup).
class AlbedoSlice {
 public:
  // Empty: set a roughness before reading it. Set in place, as a copy of a new slice was read
  // back in other widths than it was just written in, a store-forwarding stall per hit.
  AlbedoSlice() = default;
  void set_roughness(float roughness);
  float albedo(float mu) const { return at(e0_, e1_, mu); }  // E
  float schlick_share(float mu) const { return at(s0_, s1_, mu); }  // E5 / E
  float albedo_average = 1.0f, share_average = 0.0f;  // avg(E), avg(E5 / E)

 private:
  float at(const float* row0, const float* row1, float mu) const {
    const float s = (mu < 0.0f ? 0.0f : mu > 1.0f ? 1.0f : mu) * static_cast<float>(kAlbedoMu - 1);
    const int i = static_cast<int>(s) < kAlbedoMu - 2 ? static_cast<int>(s) : kAlbedoMu - 2;
    const float f = s - static_cast<float>(i);
    const float a = row0[i] + f * (row0[i + 1] - row0[i]), b = row1[i] + f * (row1[i + 1] - row1[i]);
    return a + t_ * (b - a);
  }
  const float *e0_ = nullptr, *e1_ = nullptr, *s0_ = nullptr, *s1_ = nullptr;  // the rows about the roughness
  float t_ = 0.0f;  // the upper row's weight
};

// E and E5 / E of the anisotropic lobe; azimuth = |angle| in radians between wo's projection
// on the surface and the anisotropy direction, folded into [0, pi/2].
struct AnisotropicAlbedo {
  float albedo = 1.0f, schlick_share = 0.0f;
};
AnisotropicAlbedo anisotropic_ggx_albedo(float mu, float azimuth, float roughness, float strength);

struct InterfaceAlbedo {
  float reflect = 1.0f, transmit = 0.0f;
};
InterfaceAlbedo dielectric_albedo(float mu, float roughness, float eta);
// avg(reflect / (reflect + transmit)): the compensated interface's average reflectance.
float dielectric_reflectance_average(float roughness, float eta);

// Directions for the conductor's multiple-scattering lobe, whose cosine-weighted shape is
// (1 - E(mu)) mu: mu from a piecewise-constant density over the mu grid, in proportion to
// that shape's integral per interval on the grid row nearest `roughness` (so the
// sample's weight stays within a small factor of its mean, where a cosine distribution
// would give weights of 1 / (1 - avg(E)) at grazing angles), phi uniform.
// The density is over mu; a direction's solid-angle density is it over 2 pi. Found once per
// shading point: its pdf is read at every light sample's direction.
class MultiScatterShape {
 public:
  MultiScatterShape() = default;  // no lobe: set one before reading it
  explicit MultiScatterShape(float roughness);
  float sample_mu(float u) const;
  float pdf_mu(float mu) const {
    if (mu <= 0.0f || mu > 1.0f) return 0.0f;
    const float s = mu * static_cast<float>(kAlbedoMu - 1);
    const int i = static_cast<int>(s) < kAlbedoMu - 2 ? static_cast<int>(s) : kAlbedoMu - 2;
    return (cdf_[i + 1] - cdf_[i]) * static_cast<float>(kAlbedoMu - 1);
  }

 private:
  const float* cdf_ = nullptr;  // the row's cumulative shares at the mu grid's points
};

}  // namespace tessera
