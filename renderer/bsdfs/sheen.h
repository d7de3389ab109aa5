// The sheen layer of KHR_materials_sheen: Estevez and Kulla's "Charlie" distribution with
// Ashikhmin's visibility term, and its directional albedo E(cos, roughness), tabulated once
// by quadrature, which scales down the layers beneath so that the sum stays below one.
#pragma once

#include "renderer/util/math.h"

namespace tessera {

// Sheen roughness below this is treated as this: the Charlie exponent 1/alpha blows up.
constexpr float kMinSheenAlpha = 0.07f;

struct CharlieSheen {
  float alpha;  // sheenRoughness squared

  float D(const vec3& h) const {
    const float inv = 1.0f / alpha;
    const float sin2 = fmax_inline(0.0f, 1.0f - h.z * h.z);
    return (2.0f + inv) * std::pow(sin2, 0.5f * inv) * (0.5f * kInvPi);
  }
  // f without the sheen colour; wo, wi in the upper hemisphere.
  float eval(const vec3& wo, const vec3& wi) const {
    if (wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
    const vec3 h = glm::normalize(wo + wi);
    return D(h) / (4.0f * (wi.z + wo.z - wi.z * wo.z));
  }
};

// Directional albedo of the sheen BRDF (colour 1) for a direction with cosine `cos_theta`.
float sheen_albedo(float cos_theta, float alpha);

}  // namespace tessera
