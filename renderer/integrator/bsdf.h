// The BSDF at a shading point, in the local frame of the shading normal (z up).
// A plain struct with inline functions: no virtual call per ray. For now it is Lambertian
// reflection; the glTF microfacet model extends this struct, not the integrator.
#pragma once

#include "renderer/math.h"

namespace tessera {

struct BsdfSample {
  vec3 wi{0.0f};  // local frame
  vec3 f{0.0f};  // BSDF value
  float pdf = 0.0f;  // solid angle
};

// Cosine-weighted direction on the upper hemisphere (Malley's method).
inline vec3 sample_cosine_hemisphere(const vec2& u) {
  const vec2 d = sample_concentric_disk(u);
  return {d.x, d.y, std::sqrt(std::fmax(0.0f, 1.0f - d.x * d.x - d.y * d.y))};
}

struct Bsdf {
  vec3 albedo{0.0f};

  // wo, wi in the local frame; reflection only, both in the upper hemisphere.
  vec3 eval(const vec3& wo, const vec3& wi) const {
    return wo.z > 0.0f && wi.z > 0.0f ? albedo * kInvPi : vec3(0.0f);
  }
  float pdf(const vec3& wo, const vec3& wi) const {
    return wo.z > 0.0f && wi.z > 0.0f ? wi.z * kInvPi : 0.0f;
  }
  bool sample(const vec3& wo, const vec2& u, BsdfSample& s) const {
    if (wo.z <= 0.0f) return false;
    s.wi = sample_cosine_hemisphere(u);
    s.pdf = s.wi.z * kInvPi;
    if (s.pdf <= 0.0f) return false;
    s.f = albedo * kInvPi;
    return true;
  }
};

}  // namespace tessera
