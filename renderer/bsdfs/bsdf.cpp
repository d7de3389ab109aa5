#include "renderer/bsdfs/bsdf.h"

namespace tessera {
namespace {

float max3(const vec3& v) { return max_component(v); }
float mean3(const vec3& v) { return (v.r + v.g + v.b) / 3.0f; }

}  // namespace

GltfBsdf::GltfBsdf(const ShadingPoint& sp, const vec3& wo, float eta, const Frame& frame)
    : base_(sp.base_color),
      metallic_(sp.metallic),
      transmission_(sp.transmission),
      eta_(eta),
      diffuse_transmission_(sp.diffuse_transmission),
      diffuse_transmission_color_(sp.diffuse_transmission_color),
      // An index of 1 bends nothing; the half-vector form of refraction degenerates there.
      refracts_(!sp.thin_walled && sp.transmission > 0.0f && std::fabs(sp.ior - 1.0f) > 1e-3f),
      specular_(sp.specular),
      clearcoat_(sp.clearcoat),
      roughness_(glm::clamp(sp.roughness, 0.0f, 1.0f)),
      coat_roughness_(glm::clamp(sp.clearcoat_roughness, 0.0f, 1.0f)),
      ggx_{fmax_inline(kMinAlpha, sp.roughness * sp.roughness)},
      coat_ggx_{fmax_inline(kMinAlpha, sp.clearcoat_roughness * sp.clearcoat_roughness)},
      sheen_color_(sp.sheen_color),
      sheen_{fmax_inline(kMinSheenAlpha, sp.sheen_roughness * sp.sheen_roughness)},
      sheen_max_(max_component(sp.sheen_color)) {
  // A volume of index 1 is invisible: its microfacets bend nothing, whatever their roughness
  // (treating it as thin-walled, as refracts_ does, must not blur it either).
  if (!sp.thin_walled && transmission_ > 0.0f && !refracts_) {
    ggx_ = GgxDistribution(kMinAlpha);
    roughness_ = 0.0f;
  }
  const float r = (sp.ior - 1.0f) / (sp.ior + 1.0f);
  f0_ = glm::min(vec3(r * r) * sp.specular_color, vec3(1.0f));
  f0_max_ = max3(f0_);
  spec_f0_ = f0_;
  metal_f0_ = base_;
  // The film sits on the outside: a ray inside a volume meets the bare interface.
  if (sp.iridescence > 0.0f && sp.iridescence_thickness > 0.0f && (!refracts_ || eta >= 1.0f)) {
    iridescence_ = sp.iridescence;
    film_ = ThinFilm{sp.iridescence_thickness, sp.iridescence_ior, 1.0f + 0.5f * clearcoat_};
  }
  orient_lobes(sp, frame, wo);
  compensate(wo);
  // Selection probabilities: each lobe's share of the reflected energy, estimated at the
  // macro normal. Every lobe that can be non-zero keeps a non-zero probability. A smooth
  // refracting interface reflects Fresnel's share exactly: the albedo tables' 32 cosines
  // smear its steep rise inside glass towards the critical angle, where a lobe chosen by the
  // smeared share weighed 0.2 to 3.8 (a variance of 0.12-0.2 per crossing, against 0.003-0.01),
  // and under total internal reflection its transmission keeps a floor of 0.001, not 0.05
  // (the 5% of samples it wasted there were a variance of 0.05 per reflection).
  const bool smooth_interface = refracts_ && ggx_.alpha_x <= kMinAlpha && ggx_.alpha_y <= kMinAlpha;
  const vec3 fo = smooth_interface ? refracting_fresnel(wo.z) : reflectance_o_;
  const float transmission_floor = smooth_interface ? 0.001f : 0.05f;
  const float dielectric = 1.0f - metallic_;
  const float tint = fmax_inline(luminance(base_), 1e-3f);
  sheen_scaling_o_ = sheen_scaling(wo);
  const float under_sheen = sheen_scaling_o_;
  if (!refracts_ && transmission_ > 0.0f)
    straight_ = coat_scale_ * under_sheen * dielectric * transmission_ * (vec3(1.0f) - fo) * base_;
  // Named values, not an array: stored in parts and read back whole, an array stalled on its
  // stores. Each lobe under the sheen and the coat is scaled by what passes them.
  auto layered = [&](float w) { return w * under_sheen * coat_scale_; };
  const float diffuse = dielectric * (1.0f - transmission_) * (1.0f - mean3(fo));
  const float w_diffuse = layered(diffuse * (1.0f - diffuse_transmission_) * luminance(base_));
  const float w_diffuse_transmission = layered(diffuse * diffuse_transmission_ * luminance(diffuse_transmission_color_));
  const float metal_specular = metallic_ * max3(metal_fresnel(wo.z) * metal_scale_) * e_o_;
  const float w_specular = layered(metal_specular + dielectric * mean3(fo));
  const float w_multiscatter =
      layered(metallic_ * (1.0f - e_o_) * max3(multiscatter_color_) * kPi * (1.0f - base_albedo_.albedo_average));
  const float w_transmission = layered(dielectric * transmission_ * fmax_inline(1.0f - mean3(fo), transmission_floor) * tint);
  const float w_sheen = (sheen_max_ > 0.0f ? sheen_max_ * sheen_albedo(wo.z, sheen_.alpha) : 0.0f) * coat_scale_;
  const float w_clearcoat = 1.0f - coat_scale_;  // the coat's compensated reflectance
  const float total = w_diffuse + w_diffuse_transmission + w_specular + w_multiscatter + w_transmission +
                      w_sheen + w_clearcoat;
  auto share = [total](float w) { return total > 0.0f ? w / total : 0.0f; };
  weight_[kDiffuse] = share(w_diffuse);
  weight_[kDiffuseTransmission] = share(w_diffuse_transmission);
  weight_[kSpecular] = share(w_specular);
  weight_[kMultiScatter] = share(w_multiscatter);
  weight_[kTransmission] = share(w_transmission);
  weight_[kSheen] = share(w_sheen);
  weight_[kClearcoat] = share(w_clearcoat);
  if (refracts_) {  // what interface_share() needs: the two lobes' weights as lines in F
    interface_r0_ = layered(metal_specular);
    interface_kr_ = layered(dielectric);
    interface_kt_ = layered(dielectric * transmission_ * tint);
  }
  lambda_o_ = ggx_.lambda(wo);
  g1_o_ = 1.0f / (1.0f + lambda_o_);
  specular_pdf_scale_ = g1_o_ / (4.0f * wo.z);
}

// KHR_materials_anisotropy (the specification's alpha_t = mix(alpha, 1, strength^2) along the
// direction, alpha_b = alpha across; its albedo toward wo from its own table, and the
// isotropic tables, for what lies under the specular layer, at the root mean square of the
// two alphas) and the clear coat's own normal, both from world directions into the shading
// frame.
void GltfBsdf::orient_lobes(const ShadingPoint& sp, const Frame& frame, const vec3& wo) {
  if (sp.anisotropy > 0.0f && sp.anisotropy_direction != vec3(0.0f) && !refracts_) {
    const vec3 d = frame.to_local(sp.anisotropy_direction);
    const float len = std::sqrt(d.x * d.x + d.y * d.y);
    if (len > 1e-6f) {
      const float alpha = ggx_.alpha_x, along = alpha + (1.0f - alpha) * sqr(sp.anisotropy);
      const vec2 axis = vec2(d.x, d.y) / len;
      ggx_ = GgxDistribution(along, alpha, axis);
      const float r = roughness_;
      roughness_ = std::sqrt(std::sqrt(0.5f * (along * along + alpha * alpha)));
      const float projected = std::sqrt(wo.x * wo.x + wo.y * wo.y);
      const float azimuth = projected > 1e-6f ? std::acos(fmin_inline(1.0f, std::fabs(glm::dot(vec2(wo.x, wo.y), axis)) / projected)) : 0.0f;
      anisotropic_o_ = anisotropic_ggx_albedo(wo.z, azimuth, r, sp.anisotropy);
    }
  }
  if (clearcoat_ > 0.0f && sp.clearcoat_normal != vec3(0.0f)) {
    vec3 n = frame.to_local(sp.clearcoat_normal);
    if (n.z < 0.0f) n = -n;  // the side the base's frame was turned to
    if (glm::dot(n, wo) > 0.0f && n.z > 1e-3f) {
      coat_frame_ = Frame::from_normal(glm::normalize(n));
      coat_tilted_ = true;
    }
  }
}

// The albedo tables' factors for this material and wo (see the header).
void GltfBsdf::compensate(const vec3& wo) {
  const float mu = wo.z;
  base_albedo_.set_roughness(roughness_);
  if (iridescence_ > 0.0f) {
    if (metallic_ < 1.0f) film_f0_ = schlick_refit(thin_film_reflectance(film_, mu, f0_), mu);
    if (metallic_ > 0.0f) metal_film_f0_ = schlick_refit(thin_film_reflectance(film_, mu, base_), mu);
    // Schlick's curve is linear in f0: mixing two curves is one curve (the film's, mixed in).
    spec_f0_ = glm::mix(f0_, film_f0_, iridescence_);
    metal_f0_ = glm::mix(base_, metal_film_f0_, iridescence_);
  }
  const bool anisotropic = anisotropic_o_.schlick_share >= 0.0f;
  e_o_ = anisotropic ? anisotropic_o_.albedo : base_albedo_.albedo(mu);
  if (refracts_) {
    const InterfaceAlbedo a = dielectric_albedo(mu, roughness_, eta_);
    interface_scale_ = 1.0f / fmax_inline(a.reflect + a.transmit, 1e-3f);
    reflectance_o_ = with_film(vec3(a.reflect * interface_scale_), mu);  // base_reflectance(mu), read once
  } else {
    interface_scale_ = 1.0f / fmax_inline(e_o_, 1e-3f);
    // Toward wo, an anisotropic lobe reflects its own share; the base's layering stays on
    // the isotropic tables (for wi and the average), so the base takes exactly the rest.
    reflectance_o_ = anisotropic ? with_film(vec3(specular_ * (f0_max_ + (1.0f - f0_max_) * anisotropic_o_.schlick_share)), mu)
                                 : base_reflectance(mu);
  }
  vec3 e_avg(refracts_ ? dielectric_reflectance_average(roughness_, eta_)
                       : specular_ * (f0_max_ + (1.0f - f0_max_) * base_albedo_.share_average));
  if (iridescence_ > 0.0f)
    e_avg = glm::mix(e_avg, film_scale() * (film_f0_ + (vec3(1.0f) - film_f0_) * base_albedo_.share_average), iridescence_);
  auto base_scale = [&](int c) { return e_avg[c] < 1.0f - 1e-4f ? (1.0f - reflectance_o_[c]) / (1.0f - e_avg[c]) : 0.0f; };
  // Without a film both are grey: one quotient serves the three channels.
  base_scale_o_ = iridescence_ > 0.0f ? vec3(base_scale(0), base_scale(1), base_scale(2)) : vec3(base_scale(0));
  // Kulla and Conty: the Fresnel average of Schlick's f0..1 is f0 + (1 - f0) / 21, and the
  // light that leaves after k > 1 bounces sums to F_avg^2 E_avg / (1 - F_avg (1 - E_avg)) of
  // the lost share. Below 1e-4 lost on average there is nothing to restore.
  // An anisotropic metal is scaled instead (Turquin 2019: 1 + F0 (1 - E) / E, exact for
  // F = 1), as its lost light depends on wo's azimuth, which the isotropic lobe cannot follow.
  const float e_avg_metal = base_albedo_.albedo_average;
  if (metallic_ > 0.0f && anisotropic) {
    metal_scale_ = vec3(1.0f) + metal_f0_ * ((1.0f - e_o_) / fmax_inline(e_o_, 1e-3f));
  } else if (metallic_ > 0.0f && e_avg_metal < 1.0f - 1e-4f) {
    const vec3 f_avg = metal_f0_ + (vec3(1.0f) - metal_f0_) / 21.0f;
    const vec3 f_ms = f_avg * f_avg * e_avg_metal / (vec3(1.0f) - f_avg * (1.0f - e_avg_metal));
    multiscatter_color_ = f_ms / (kPi * (1.0f - e_avg_metal));
    multiscatter_shape_ = MultiScatterShape(roughness_);
  }
  if (clearcoat_ > 0.0f) {
    const float mu_coat = coat_tilted_ ? coat_frame_.to_local(wo).z : mu;
    coat_albedo_.set_roughness(coat_roughness_);
    coat_interface_scale_ = 1.0f / fmax_inline(coat_albedo_.albedo(mu_coat), 1e-3f);
    const float reflectance = 0.04f + 0.96f * coat_albedo_.schlick_share(mu_coat);
    coat_scale_ = 1.0f - clearcoat_ * reflectance;
  } else {
    coat_scale_ = 1.0f;
  }
}

vec3 GltfBsdf::refracting_reflectance(float mu) const {
  const InterfaceAlbedo a = dielectric_albedo(mu, roughness_, eta_);
  return with_film(vec3(a.reflect / fmax_inline(a.reflect + a.transmit, 1e-3f)), mu);
}

// The film layer's e(mu): its Schlick curve's microfacet average, from the tables.
vec3 GltfBsdf::film_reflectance(float mu) const {
  return film_f0_ + (vec3(1.0f) - film_f0_) * base_albedo_.schlick_share(mu);
}

// The f0 of the Schlick curve through reflectance f at mu (near grazing, where every curve
// nears 1 and the fit degenerates, read at mu = 0.05). Where the film cancels more than a
// bare surface reflects there (f below Schlick's curve for f0 = 0, only toward grazing),
// f0 = 0: the curve then passes above f, but stays a reflectance the tables hold.
vec3 GltfBsdf::schlick_refit(const vec3& f, float mu) {
  const float m = 1.0f - fmax_inline(mu, 0.05f), p = m * m * m * m * m;
  return glm::clamp((f - p) / (1.0f - p), 0.0f, 1.0f);
}

vec3 GltfBsdf::multiscatter(const vec3& wo, const vec3& wi) const {
  if (multiscatter_color_ == vec3(0.0f) || wi.z <= 0.0f) return vec3(0.0f);
  return multiscatter_color_ * ((1.0f - e_o_) * (1.0f - base_albedo_.albedo(wi.z)));
}

float GltfBsdf::sheen_scaling(const vec3& w) const {
  return sheen_max_ > 0.0f ? 1.0f - sheen_max_ * sheen_albedo(std::fabs(w.z), sheen_.alpha) : 1.0f;
}

vec3 GltfBsdf::refracting_fresnel(float cos_oh) const {
  const vec3 f(fresnel_dielectric(cos_oh, eta_));
  return iridescence_ > 0.0f ? glm::mix(f, fresnel_schlick(film_f0_, vec3(1.0f), cos_oh), iridescence_) : f;
}

float GltfBsdf::coat_fresnel(float cos_o) const {
  if (clearcoat_ <= 0.0f) return 0.0f;
  return fresnel_schlick(vec3(0.04f), vec3(1.0f), cos_o).x;  // coat ior 1.5
}

GltfBsdf::HalfVector GltfBsdf::half_vector(const vec3& wo, const vec3& wi) const {
  if (wi.z <= 0.0f) return {};
  HalfVector m;
  m.h = glm::normalize(wo + wi);
  m.cos_oh = glm::dot(wo, m.h);
  m.d = ggx_.D(m.h);
  return m;
}

vec3 GltfBsdf::reflection(const vec3& wo, const vec3& wi, const HalfVector& m) const {
  const float cos_oh = m.cos_oh;
  const float spec = m.d / ((1.0f + lambda_o_ + ggx_.lambda(wi)) * (4.0f * wo.z * wi.z));  // D G2 / (4 cos cos)
  vec3 f(0.0f);
  if (metallic_ < 1.0f) {
    const vec3 base_share = base_scale_o_ * (vec3(1.0f) - base_reflectance(wi.z));
    f = (1.0f - metallic_) * ((1.0f - transmission_) * (1.0f - diffuse_transmission_) * base_share * base_ * kInvPi +
                              dielectric_fresnel(cos_oh) * (spec * interface_scale_));
  }
  if (metallic_ > 0.0f) f += metallic_ * (metal_fresnel(cos_oh) * metal_scale_ * spec + multiscatter(wo, wi));
  return f;
}

vec3 GltfBsdf::transmission(const vec3& wo, const vec3& wi) const {
  if (!refracts_ || metallic_ >= 1.0f) return vec3(0.0f);  // thin: a straight pass, not evaluable
  vec3 h;
  if (!refraction_normal(wo, wi, h)) return vec3(0.0f);
  const float cos_oh = glm::dot(wo, h), cos_ih = glm::dot(wi, h);
  if (cos_oh <= 0.0f || cos_ih >= 0.0f) return vec3(0.0f);  // back-facing microfacet
  const float denom = sqr(cos_ih + cos_oh / eta_) * std::fabs(wi.z) * wo.z;
  // Radiance is compressed by eta^2 entering a denser medium (non-symmetric scattering).
  const float ft = ggx_.D(h) * ggx_.G2(wo, wi) * std::fabs(cos_ih * cos_oh / denom) / sqr(eta_);
  return (1.0f - metallic_) * transmission_ * interface_scale_ * base_ * (vec3(1.0f) - dielectric_fresnel(cos_oh)) * ft;
}

// The Lambertian transmission of the diffuse base, layered under the interface like the
// diffuse reflection (the cosine toward wi taken on its side).
vec3 GltfBsdf::diffuse_transmission(const vec3& wo, const vec3& wi) const {
  if (diffuse_transmission_ <= 0.0f) return vec3(0.0f);
  const vec3 base_share = base_scale_o_ * (vec3(1.0f) - base_reflectance(-wi.z));
  return (1.0f - metallic_) * (1.0f - transmission_) * diffuse_transmission_ * base_share *
         diffuse_transmission_color_ * kInvPi;
}

vec3 GltfBsdf::eval(const vec3& wo, const vec3& wi) const { return eval(wo, wi, half_vector(wo, wi)); }

vec3 GltfBsdf::eval(const vec3& wo, const vec3& wi, float& pdf) const {
  const HalfVector m = half_vector(wo, wi);
  pdf = this->pdf(wo, wi, m);
  return eval(wo, wi, m);
}

vec3 GltfBsdf::eval(const vec3& wo, const vec3& wi, const HalfVector& m) const {
  if (wo.z <= 0.0f || wi.z == 0.0f) return vec3(0.0f);
  const float under_sheen = fmin_inline(sheen_scaling_o_, sheen_scaling(wi));
  if (wi.z < 0.0f) return coat_scale_ * under_sheen * (transmission(wo, wi) + diffuse_transmission(wo, wi));
  vec3 f = under_sheen * reflection(wo, wi, m);
  if (sheen_max_ > 0.0f) f += sheen_color_ * sheen_.eval(wo, wi);  // without a sheen it adds 0
  f = coat_scale_ * f;
  if (clearcoat_ > 0.0f) f += coat(wo, wi);
  return f;
}

// In the coat's frame; times cos_coat(wi) / cos(wi), because the integrator weighs by the
// base normal's cosine and the coat's light falls on its own.
vec3 GltfBsdf::coat(const vec3& wo, const vec3& wi) const {
  const vec3 o = coat_tilted_ ? coat_frame_.to_local(wo) : wo, i = coat_tilted_ ? coat_frame_.to_local(wi) : wi;
  if (o.z <= 0.0f || i.z <= 0.0f) return vec3(0.0f);
  const vec3 h = glm::normalize(o + i);
  const float f = clearcoat_ * coat_fresnel(glm::dot(o, h)) * coat_interface_scale_ * coat_ggx_.D(h) *
                  coat_ggx_.G2(o, i) / (4.0f * o.z * i.z);
  return vec3(coat_tilted_ ? f * i.z / wi.z : f);
}

float GltfBsdf::coat_pdf(const vec3& wo, const vec3& wi) const {
  const vec3 o = coat_tilted_ ? coat_frame_.to_local(wo) : wo, i = coat_tilted_ ? coat_frame_.to_local(wi) : wi;
  if (o.z <= 0.0f || i.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
  const vec3 h = glm::normalize(o + i);
  return coat_ggx_.visible_pdf(o, h) / (4.0f * glm::dot(o, h));
}

const char* GltfBsdf::lobe_name(int lobe) {
  static const char* const kNames[] = {"diffuse", "diffuse transmission", "specular", "multiple scattering",
                                       "transmission", "sheen", "clearcoat"};
  if (lobe == kGuided) return "guided";
  return lobe >= 0 && lobe < kLobeCount ? kNames[lobe] : "none";
}

// Inlined into pdf()'s loop, unrolled there: each lobe's case then stands alone.
[[gnu::always_inline]] inline float GltfBsdf::lobe_pdf(int lobe, const vec3& wo, const vec3& wi, const HalfVector& m) const {
  switch (lobe) {
    case kDiffuse:
    case kSheen: return wi.z > 0.0f ? wi.z * kInvPi : 0.0f;
    case kMultiScatter: return wi.z > 0.0f ? multiscatter_shape_.pdf_mu(wi.z) * (0.5f * kInvPi) : 0.0f;
    case kDiffuseTransmission: return wi.z < 0.0f ? -wi.z * kInvPi : 0.0f;
    case kClearcoat: return coat_pdf(wo, wi);
    case kSpecular:  // G1(wo) max(0, wo.h) D(h) / wo.z over the reflection's 4 wo.h
      return wi.z > 0.0f && m.cos_oh > 0.0f ? m.d * specular_pdf_scale_ : 0.0f;
    default: {  // transmission
      if (wi.z >= 0.0f || !refracts_) return 0.0f;  // the thin pass is a delta
      vec3 h;
      return refraction_normal(wo, wi, h) ? transmission_pdf(wo, wi, h) : 0.0f;
    }
  }
}

// The microfacet normal (on wo's side) that refracts wo into wi; false where there is none.
bool GltfBsdf::refraction_normal(const vec3& wo, const vec3& wi, vec3& h) const {
  h = wi * eta_ + wo;
  if (glm::dot(h, h) <= 0.0f) return false;
  h = glm::normalize(h);
  if (h.z < 0.0f) h = -h;
  return true;
}

// The transmission lobe's pdf of wi, refracted by the microfacet h (refraction_normal).
float GltfBsdf::transmission_pdf(const vec3& wo, const vec3& wi, const vec3& h) const {
  const float cos_oh = glm::dot(wo, h), cos_ih = glm::dot(wi, h);
  if (cos_oh <= 0.0f || cos_ih >= 0.0f) return 0.0f;
  return ggx_.visible_pdf(wo, h) * std::fabs(cos_ih) / sqr(cos_ih + cos_oh / eta_);
}

float GltfBsdf::pdf(const vec3& wo, const vec3& wi) const { return pdf(wo, wi, half_vector(wo, wi)); }

float GltfBsdf::pdf(const vec3& wo, const vec3& wi, const HalfVector& m) const {
  if (wo.z <= 0.0f || wi.z == 0.0f) return 0.0f;
  float p = 0.0f;
  if (refracts_) {  // the interface's two lobes as sample() chooses them (interface_share)
    p = interface_pdf(wo, wi, m);
#pragma GCC unroll 8
    for (int i = 0; i < kLobeCount; ++i)
      if (weight_[i] > 0.0f && i != kSpecular && i != kTransmission) p += weight_[i] * lobe_pdf(i, wo, wi, m);
    return p;
  }
#pragma GCC unroll 8
  for (int i = 0; i < kLobeCount; ++i)
    if (weight_[i] > 0.0f) p += weight_[i] * lobe_pdf(i, wo, wi, m);
  return p;
}

float GltfBsdf::interface_pdf(const vec3& wo, const vec3& wi, const HalfVector& m) const {
  const float both = weight_[kSpecular] + weight_[kTransmission];
  if (!(both > 0.0f)) return 0.0f;
  if (wi.z > 0.0f) {
    if (m.cos_oh <= 0.0f) return 0.0f;
    return both * interface_share(m.cos_oh) * lobe_pdf(kSpecular, wo, wi, m);
  }
  vec3 h;
  if (!refraction_normal(wo, wi, h)) return 0.0f;
  const float cos_oh = glm::dot(wo, h);
  if (cos_oh <= 0.0f) return 0.0f;
  return both * (1.0f - interface_share(cos_oh)) * transmission_pdf(wo, wi, h);
}

bool GltfBsdf::sample(const vec3& wo, float u_lobe, const vec2& u, BsdfSample& s) const {
  if (wo.z <= 0.0f) return false;
  int lobe = 0;
  float acc = weight_[0];
  for (; lobe < kLobeCount - 1 && u_lobe >= acc; acc += weight_[++lobe]) {}
  if (weight_[lobe] <= 0.0f) return false;
  vec3 wi;
  if (refracts_ && (lobe == kSpecular || lobe == kTransmission)) {
    // The interface: reflection or refraction at the sampled microfacet, by its own Fresnel.
    // u_lobe's place within the two lobes' weights, as one interval, chooses.
    const float both = weight_[kSpecular] + weight_[kTransmission];
    const float v = fmin_inline((u_lobe - (acc - weight_[lobe])) / weight_[lobe], 0x1.fffffep-1f);
    const float place = (lobe == kSpecular ? v * weight_[kSpecular] : weight_[kSpecular] + v * weight_[kTransmission]) / both;
    const vec3 h = ggx_.sample_visible(wo, u);
    lobe = place < interface_share(glm::dot(wo, h)) ? kSpecular : kTransmission;
    if (lobe == kSpecular) wi = reflect(wo, h);
    else if (!refract(wo, h, eta_, wi)) return false;  // total internal reflection: its share was 1
    s.lobe = lobe;
    return finish_sample(wo, wi, lobe, s);
  }
  s.lobe = lobe;
  switch (lobe) {
    case kDiffuse:
    case kSheen: wi = sample_cosine_hemisphere(u); break;
    case kDiffuseTransmission: wi = -sample_cosine_hemisphere(u); break;
    case kSpecular: wi = reflect(wo, ggx_.sample_visible(wo, u)); break;
    case kMultiScatter: {
      const float mu = multiscatter_shape_.sample_mu(u.x), r = std::sqrt(fmax_inline(0.0f, 1.0f - mu * mu));
      const float phi = 2.0f * kPi * u.y;
      wi = {r * std::cos(phi), r * std::sin(phi), mu};
      break;
    }
    case kClearcoat: {
      const vec3 o = coat_tilted_ ? coat_frame_.to_local(wo) : wo;
      const vec3 i = reflect(o, coat_ggx_.sample_visible(o, u));
      if (i.z <= 0.0f) return false;  // below the coat: where its pdf is zero
      wi = coat_tilted_ ? coat_frame_.to_world(i) : i;
      break;
    }
    default: {
      if (!refracts_) {  // thin-walled: straight through, weight straight_ / probability
        s.set_wi(-wo);
        s.f = straight_ / wo.z;
        s.pdf = weight_[kTransmission];
        s.transmitted = s.passthrough = true;
        return s.pdf > 0.0f;
      }
      if (!refract(wo, ggx_.sample_visible(wo, u), eta_, wi)) return false;  // total internal reflection
    }
  }
  return finish_sample(wo, wi, lobe, s);
}

bool GltfBsdf::finish_sample(const vec3& wo, const vec3& wi, int lobe, BsdfSample& s) const {
  s.set_wi(wi);
  const bool below = lobe == kTransmission || lobe == kDiffuseTransmission;
  if (below ? s.wi.z >= 0.0f : s.wi.z <= 0.0f) return false;
  s.f = eval(wo, s.wi, s.pdf);
  s.transmitted = below;
  return s.pdf > 0.0f && std::isfinite(s.pdf);
}

// Reflection's share of a refracting interface at a microfacet whose cosine with wo is cos_oh:
// the lobes' weights (reflection r0 + kr F, refraction kt (1 - F)) with that microfacet's
// exact Fresnel F. Chosen by the macro normal's Fresnel, as the lobe weights are, a
// microfacet tilted past the critical angle's edge refracted with the transmission's floor
// probability (0.1%) and weighed up to 1000 (a firefly where light leaves glass at the critical
// angle); chosen by its own, each sample weighs G2/G1 and the interface's scale at most.
float GltfBsdf::interface_share(float cos_oh) const {
  const float f = mean3(refracting_fresnel(cos_oh));
  const float r = interface_r0_ + interface_kr_ * f, t = interface_kt_ * (1.0f - f);
  return r + t > 0.0f ? r / (r + t) : 1.0f;
}

}  // namespace tessera
