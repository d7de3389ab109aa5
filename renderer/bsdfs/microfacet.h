// Trowbridge-Reitz (GGX) microfacets with height-correlated Smith masking, sampled through
// the distribution of visible normals, and the Fresnel terms the glTF model uses.
// Directions are in the local shading frame (z = normal).
#pragma once

#include "renderer/util/math.h"

namespace tessera {

// Roughness below this is treated as this: a mirror sharp to far below a pixel, without
// the special cases of a delta distribution.
constexpr float kMinAlpha = 1e-3f;

inline float sqr(float x) { return x * x; }

// Anisotropic when alpha_x != alpha_y: alpha_x along `axis` (a unit direction in the
// tangent plane of the local frame, KHR_materials_anisotropy's direction), alpha_y across.
struct GgxDistribution {
  float alpha_x, alpha_y;
  vec2 axis{1.0f, 0.0f};

  GgxDistribution(float alpha) : alpha_x(alpha), alpha_y(alpha) {}  // isotropic
  GgxDistribution(float ax, float ay, vec2 direction) : alpha_x(ax), alpha_y(ay), axis(direction) {}

  // w in the frame whose x is the axis.
  vec3 to_axis(const vec3& w) const { return {axis.x * w.x + axis.y * w.y, axis.x * w.y - axis.y * w.x, w.z}; }
  vec3 from_axis(const vec3& w) const { return {axis.x * w.x - axis.y * w.y, axis.y * w.x + axis.x * w.y, w.z}; }

  float D(const vec3& m_local) const {
    if (m_local.z <= 0.0f) return 0.0f;
    const vec3 m = to_axis(m_local);
    const float t = sqr(m.x / alpha_x) + sqr(m.y / alpha_y) + m.z * m.z;
    return 1.0f / (kPi * alpha_x * alpha_y * t * t);
  }
  // Smith's auxiliary function: G1 = 1 / (1 + lambda).
  float lambda(const vec3& w_local) const {
    const float cos2 = w_local.z * w_local.z;
    if (cos2 <= 0.0f) return 0.0f;
    const vec3 w = to_axis(w_local);
    const float a2_tan2 = (sqr(alpha_x * w.x) + sqr(alpha_y * w.y)) / cos2;
    return 0.5f * (std::sqrt(1.0f + a2_tan2) - 1.0f);
  }
  float G1(const vec3& w) const { return 1.0f / (1.0f + lambda(w)); }
  // Height-correlated masking-shadowing (Heitz 2014), as the glTF specification uses; the
  // second form from the two lambdas, for a caller that keeps wo's per shading point.
  float G2(const vec3& wo, const vec3& wi) const { return G2(lambda(wo), lambda(wi)); }
  static float G2(float lambda_o, float lambda_i) { return 1.0f / (1.0f + lambda_o + lambda_i); }

  // Density of the normals visible from w (w.z > 0): G1(w) max(0, w.m) D(m) / w.z; the
  // second form from those parts (G1(w) kept per shading point, D(m) shared with f).
  float visible_pdf(const vec3& w, const vec3& m) const { return visible_pdf(G1(w), w.z, glm::dot(w, m), D(m)); }
  static float visible_pdf(float g1, float wz, float wm, float d) {
    return wm > 0.0f && wz > 0.0f ? g1 * wm * d / wz : 0.0f;
  }

  // A visible normal for w (w.z > 0), Heitz 2018, "Sampling the GGX Distribution of
  // Visible Normals": stretch to the unit-roughness configuration, sample, unstretch.
  vec3 sample_visible(const vec3& w_local, const vec2& u) const {
    const vec3 w = to_axis(w_local);
    const vec3 vh = glm::normalize(vec3(alpha_x * w.x, alpha_y * w.y, w.z));
    const float len2 = vh.x * vh.x + vh.y * vh.y;
    const vec3 t1 = len2 > 0.0f ? vec3(-vh.y, vh.x, 0.0f) / std::sqrt(len2) : vec3(1.0f, 0.0f, 0.0f);
    const vec3 t2 = glm::cross(vh, t1);
    const float r = std::sqrt(u.x), phi = 2.0f * kPi * u.y;
    const float p1 = r * std::cos(phi);
    const float s = 0.5f * (1.0f + vh.z);
    const float p2 = (1.0f - s) * std::sqrt(fmax_inline(0.0f, 1.0f - p1 * p1)) + s * r * std::sin(phi);
    const vec3 nh = p1 * t1 + p2 * t2 + std::sqrt(fmax_inline(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
    return from_axis(glm::normalize(vec3(alpha_x * nh.x, alpha_y * nh.y, fmax_inline(1e-6f, nh.z))));
  }
};

inline vec3 reflect(const vec3& w, const vec3& m) { return 2.0f * glm::dot(w, m) * m - w; }

// Refracts w (on the side m points to) through microfacet m, eta = eta_other / eta_this.
// False on total internal reflection.
inline bool refract(const vec3& w, const vec3& m, float eta, vec3& out) {
  const float cos_i = glm::dot(w, m);
  const float sin2_t = fmax_inline(0.0f, 1.0f - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1.0f) return false;
  const float cos_t = std::sqrt(1.0f - sin2_t);
  out = -w / eta + (cos_i / eta - cos_t) * m;
  return true;
}

// Unpolarised Fresnel reflectance of a dielectric interface; cos_i > 0 on the side of the
// incident light, eta = eta_transmitted / eta_incident. 1 under total internal reflection.
inline float fresnel_dielectric(float cos_i, float eta) {
  cos_i = glm::clamp(cos_i, 0.0f, 1.0f);
  const float sin2_t = (1.0f - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1.0f) return 1.0f;
  const float cos_t = std::sqrt(1.0f - sin2_t);
  const float rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  const float rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  return 0.5f * (rs * rs + rp * rp);
}

// Schlick's approximation, as the glTF specification writes it.
inline vec3 fresnel_schlick(const vec3& f0, const vec3& f90, float cos_theta) {
  const float m = glm::clamp(1.0f - cos_theta, 0.0f, 1.0f);
  const float m2 = m * m;
  return f0 + (f90 - f0) * (m2 * m2 * m);
}

}  // namespace tessera
