// The glTF 2.0 BSDF (specification Appendix B and the KHR_materials_* extensions) at one
// shading point, in the local frame of the shading normal with the outgoing direction wo
// always in the upper hemisphere (the integrator flips the frame to the side the ray came
// from, and passes the matching relative index of refraction).
//
//   metal      = Schlick(baseColor, 1, wo.h) D G / (4 |cos_o cos_i|) + multiple scattering
//   interface  = [s F D G / (4 |cos cos|) + T baseColor btdf] / E_interface(mu_o)
//   dielectric = interface + (1 - T) diffuse * (1 - e(mu_o)) (1 - e(mu_i)) / (1 - avg e)
//   diffuse    = (1 - dt) baseColor / pi above, dt diffuseTransmissionColor / pi below
//   material   = mix(dielectric, metal, metallic)
//   sheened    = sheenColor * D_charlie V + material * min(1 - max(sheenColor) E(wo), same for wi)
//   coated     = (1 - c e_coat(mu_o)) * sheened + c Fc D_c G_c / (4 |cos cos| E_coat(mu_o))
// F is Schlick's with f0 = min(((ior-1)/(ior+1))^2 specularColor, 1) scaled by s = specular;
// a refracting (volume) dielectric uses the exact Fresnel term instead, so glass conserves
// energy and shows total internal reflection. btdf is a rough refraction (Walter et al.
// 2007) when the material has a volume, or, thin-walled, a straight pass through the
// surface (a delta, as pbrt-v4's thin dielectric: roughness does not blur it), which shadow
// rays also take.
//
// Energy compensation (microfacet_albedo.h): single-scattering GGX loses the light that
// bounces among the microfacets, up to 60% at roughness 1. The metal gets Kulla and Conty's
// (2017) multiple-scattering lobe, (1 - E(mu_o)) (1 - E(mu_i)) / (pi (1 - avg E)) times their
// Fresnel average term: reciprocal, and with Fresnel 1 it restores exactly what is lost. A
// dielectric interface is divided by its single-scattering albedo E_interface(mu_o) (Turquin
// 2019): reflection plus transmission then sum to 1 from every direction, the split between
// them kept; the diffuse base takes what the interface reflects, e(mu) = its compensated
// reflectance, in Kulla and Conty's reciprocal form, so a white base under any specular
// layer, and the clear coat over any lossless layer, reflect everything. The anisotropic lobe
// (KHR_materials_anisotropy) has its own albedo table per strength and wo's azimuth; its
// metal is scaled by 1 + F0 (1 - E(wo)) / E(wo) (Turquin) instead of the extra lobe.
// KHR_materials_iridescence mixes a thin film's Fresnel (thin_film.h) into both specular
// Fresnel terms, read once per shading point toward wo and carried by a Schlick curve the
// albedo tables hold (bsdf.cpp, with_film), so the layering stays exact.
// Directions are sampled per lobe (cosine, GGX visible normals, the multiple-scattering
// lobe's tabulated shape) and combined as a mixture whose pdf is the weighted sum of the
// lobes' pdfs. Plain struct, no virtual calls.
#pragma once

#include <xmmintrin.h>

#include <cstddef>
#include <cstring>

#include "renderer/materials/materials.h"
#include "renderer/bsdfs/microfacet.h"
#include "renderer/bsdfs/microfacet_albedo.h"
#include "renderer/bsdfs/sheen.h"
#include "renderer/bsdfs/thin_film.h"

namespace tessera {

// alignas(16) and wi_pad: GltfBsdf::sample stores wi in one 16-byte store (set_wi), which a
// caller's 8-byte load of wi.z and the float after it can then read from the store buffer; two
// 4-byte stores cannot be forwarded to it, and that wait was 12% of path_vertex's time on
// DamagedHelmet.
struct alignas(16) BsdfSample {
  vec3 wi{0.0f};  // local frame
  float wi_pad = 0.0f;
  void set_wi(const vec3& v) {
    const __m128 x = _mm_setr_ps(v.x, v.y, v.z, 0.0f);
    std::memcpy(static_cast<void*>(this), &x, sizeof x);
  }
  vec3 f{0.0f};  // BSDF value (whole mixture)
  float pdf = 0.0f;  // solid angle (whole mixture)
  bool transmitted = false;  // wi is below the surface
  // A thin-walled surface's straight pass (a delta: wi = -wo): the path goes on as if the
  // surface were not there, with f |cos| / pdf as its weight; light sampling reaches light
  // through it by the same transmittance (straight_transmittance).
  bool passthrough = false;
  int lobe = -1;  // the GltfBsdf::Lobe sampled (for --pixel's path printout)
};
static_assert(offsetof(BsdfSample, wi) == 0 && offsetof(BsdfSample, wi_pad) == 12, "set_wi stores both");

// Cosine-weighted direction on the upper hemisphere (Malley's method).
inline vec3 sample_cosine_hemisphere(const vec2& u) {
  const vec2 d = sample_concentric_disk(u);
  return {d.x, d.y, std::sqrt(fmax_inline(0.0f, 1.0f - d.x * d.x - d.y * d.y))};
}

class GltfBsdf {
 public:
  enum Lobe { kDiffuse, kDiffuseTransmission, kSpecular, kMultiScatter, kTransmission, kSheen, kClearcoat, kLobeCount };
  static constexpr int kGuided = kLobeCount;  // a BsdfSample's lobe when the path guide drew it

  // `eta` = index of refraction beyond the surface / index on the side of wo. `frame` is the
  // shading frame (world to local) for the material's world directions: the anisotropy
  // direction and the clear coat's own normal.
  GltfBsdf(const ShadingPoint& sp, const vec3& wo, float eta,
           const Frame& frame = Frame{{1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 1.0f}});

  // wo is the constructor's in every method (the lobes' weights and Smith's term toward wo
  // are kept from it).
  vec3 eval(const vec3& wo, const vec3& wi) const;
  float pdf(const vec3& wo, const vec3& wi) const;
  // Both at once, as sampling and light sampling need them: the half vector's terms once.
  vec3 eval(const vec3& wo, const vec3& wi, float& pdf) const;
  bool sample(const vec3& wo, float u_lobe, const vec2& u, BsdfSample& s) const;

  // Whether eval() can be non-zero below the surface: refraction into a volume, or diffuse
  // transmission (KHR_materials_diffuse_transmission). (A thin
  // surface's transmission is a straight pass, a delta that only sampling produces.)
  bool has_transmission() const {
    return (refracts_ && weight_[kTransmission] > 0.0f) || weight_[kDiffuseTransmission] > 0.0f;
  }
  // What a thin-walled transmissive surface lets straight through towards -wo: the share of
  // the compensated interface that is not reflected, under the sheen and the coat.
  vec3 straight_transmittance() const { return straight_; }
  float lobe_probability(Lobe lobe) const { return weight_[lobe]; }
  static const char* lobe_name(int lobe);  // "diffuse", "specular", ..., "guided"

 private:
  vec3 dielectric_fresnel(float cos_oh) const {  // s * F for the dielectric layer
    return refracts_ ? refracting_fresnel(cos_oh) : specular_ * fresnel_schlick(spec_f0_, vec3(1.0f), cos_oh);
  }
  vec3 refracting_fresnel(float cos_oh) const;  // exact, with the film mixed in
  vec3 metal_fresnel(float cos_oh) const { return fresnel_schlick(metal_f0_, vec3(1.0f), cos_oh); }
  float coat_fresnel(float cos_o) const;
  vec3 base_reflectance(float mu) const {  // e(mu): the compensated interface's reflectance
    if (refracts_) return refracting_reflectance(mu);
    return with_film(vec3(specular_ * (f0_max_ + (1.0f - f0_max_) * base_albedo_.schlick_share(mu))), mu);
  }
  vec3 refracting_reflectance(float mu) const;
  // KHR_materials_iridescence. The film's Fresnel is not Schlick-shaped, so the albedo tables
  // cannot hold its microfacet average. It is evaluated once per shading point, toward wo, and
  // carried by the Schlick curve through that value (film_f0_, metal_film_f0_; real-time
  // viewers evaluate it at N.V alike): exact for a mirror-like surface, whose half vector is
  // the normal, an approximation of the colour where a rough lobe's half vectors spread; the
  // layering then holds exactly, and a shading point costs one film evaluation per base.
  vec3 with_film(const vec3& e, float mu) const {  // e(mu) with the iridescent film mixed in
    return iridescence_ > 0.0f ? glm::mix(e, film_scale() * film_reflectance(mu), iridescence_) : e;
  }
  static vec3 schlick_refit(const vec3& f, float mu);
  vec3 film_reflectance(float mu) const;  // the film's e(mu), the Schlick curve through film_f0_
  float film_scale() const { return refracts_ ? 1.0f : specular_; }  // KHR_materials_specular's factor
  // wo and wi's half vector, its cosine with wo and D there: what f and the pdf share
  // (zero below the surface, where no reflection lobe reads it).
  struct HalfVector {
    vec3 h{0.0f};
    float cos_oh = 0.0f, d = 0.0f;
  };
  HalfVector half_vector(const vec3& wo, const vec3& wi) const;
  vec3 eval(const vec3& wo, const vec3& wi, const HalfVector& m) const;
  float pdf(const vec3& wo, const vec3& wi, const HalfVector& m) const;
  void compensate(const vec3& wo);
  vec3 multiscatter(const vec3& wo, const vec3& wi) const;  // the metal's extra lobe
  void orient_lobes(const ShadingPoint& sp, const Frame& frame, const vec3& wo);
  vec3 coat(const vec3& wo, const vec3& wi) const;  // the clear coat's reflection
  float coat_pdf(const vec3& wo, const vec3& wi) const;
  float lobe_pdf(int lobe, const vec3& wo, const vec3& wi, const HalfVector& m) const;
  bool refraction_normal(const vec3& wo, const vec3& wi, vec3& h) const;  // the microfacet refracting wo into wi
  float transmission_pdf(const vec3& wo, const vec3& wi, const vec3& h) const;  // of wi, refracted by h
  // A refracting interface chooses reflection or refraction per sampled microfacet:
  float interface_share(float cos_oh) const;  // reflection's share at that microfacet
  float interface_pdf(const vec3& wo, const vec3& wi, const HalfVector& m) const;  // both lobes' pdf
  bool finish_sample(const vec3& wo, const vec3& wi, int lobe, BsdfSample& s) const;  // f and pdf at wi
  vec3 reflection(const vec3& wo, const vec3& wi, const HalfVector& m) const;  // diffuse + specular, below the coat
  vec3 transmission(const vec3& wo, const vec3& wi) const;
  vec3 diffuse_transmission(const vec3& wo, const vec3& wi) const;

  vec3 base_;
  float metallic_, transmission_, eta_;
  float diffuse_transmission_;  // KHR_materials_diffuse_transmission: share of the diffuse base
  vec3 diffuse_transmission_color_;
  bool refracts_;  // a volume: refraction and exact Fresnel
  vec3 f0_;  // dielectric normal-incidence reflectance (specular colour applied)
  float specular_;
  float clearcoat_;
  float roughness_, coat_roughness_;  // of the tables' lookups
  AlbedoSlice base_albedo_, coat_albedo_;  // the tables at those roughnesses (set in compensate)
  float f0_max_;  // largest channel of f0 (before s): e(mu) of the Schlick interface follows it
  float interface_scale_ = 1.0f;  // 1 / E_interface(mu_o)
  vec3 base_scale_o_{1.0f};  // (1 - e(mu_o)) / (1 - avg e): the diffuse base's share, wo's half
  float e_o_ = 1.0f;  // E(mu_o) of the base lobe
  vec3 reflectance_o_{0.0f};  // e(mu_o): what the compensated interface reflects toward wo
  vec3 multiscatter_color_{0.0f};  // Kulla-Conty's Fresnel term / (pi (1 - avg E)); 0 = no lobe
  MultiScatterShape multiscatter_shape_;  // that lobe's sampling density, at roughness_
  vec3 metal_scale_{1.0f};  // an anisotropic metal's compensation instead of that lobe
  AnisotropicAlbedo anisotropic_o_{1.0f, -1.0f};  // the anisotropic lobe's toward wo; share < 0: isotropic
  float coat_interface_scale_ = 1.0f;  // 1 / E_coat(mu_o)
  float iridescence_ = 0.0f;  // KHR_materials_iridescence: 0 = no film
  ThinFilm film_;
  vec3 film_f0_{0.0f}, metal_film_f0_{0.0f};  // Schlick's f0 standing in for the film (dielectric, metal base)
  vec3 spec_f0_, metal_f0_;  // the specular layers' Schlick f0, film mixed in
  bool coat_tilted_ = false;  // the coat has its own normal (clearcoatNormalTexture)
  Frame coat_frame_{{1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 1.0f}};  // local to the coat's
  vec3 straight_{0.0f};  // the thin-walled straight pass; 0 for a volume or no transmission
  GgxDistribution ggx_, coat_ggx_;
  float lambda_o_ = 0.0f, g1_o_ = 1.0f;  // Smith's lambda and G1 of ggx_ toward wo
  float specular_pdf_scale_ = 0.0f;  // G1(wo) / (4 wo.z): the specular lobe's pdf over D
  vec3 sheen_color_;
  CharlieSheen sheen_;
  float sheen_max_;  // max component of the sheen colour; 0 = no sheen
  float sheen_scaling(const vec3& w) const;  // 1 - max(sheenColor) E(w): what the sheen lets through
  float sheen_scaling_o_ = 1.0f;  // toward wo
  float coat_scale_;  // 1 - clearcoat * Fc(wo): what passes the coat, for wo
  float weight_[kLobeCount];  // lobe selection probabilities for this wo, summing to 1
  // A refracting interface's lobe weights as lines in a microfacet's Fresnel F: reflection
  // r0 + kr F (r0 the metal's), refraction kt (1 - F) (interface_share).
  float interface_r0_ = 0.0f, interface_kr_ = 0.0f, interface_kt_ = 0.0f;
};

}  // namespace tessera
