// Small math helpers shared by the renderer on top of glm.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>

#include <glm/glm.hpp>

namespace tessera {

using glm::vec2;
using glm::vec3;
using glm::vec4;

constexpr float kPi = 3.14159265358979323846f;
constexpr float kInvPi = 0.31830988618379067154f;

// std::fmax and std::fmin, inline: the same result for every input (a NaN argument yields the
// other one; of two equal values, the second, as glibc's maxss/minss), but GCC calls libm for
// std::fmax and std::fmin unless -ffinite-math-only, and the shading code takes them per hit.
inline float fmax_inline(float a, float b) { return a > b || b != b ? a : b; }
inline float fmin_inline(float a, float b) { return a < b || b != b ? a : b; }

inline float luminance(const vec3& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }
inline float max_component(const vec3& c) { return fmax_inline(c.r, fmax_inline(c.g, c.b)); }
// The same bits (unlike ==, which takes -0 for +0 and no NaN for itself).
inline bool same_bits(float a, float b) {
  std::uint32_t x, y;
  std::memcpy(&x, &a, 4);
  std::memcpy(&y, &b, 4);
  return x == y;
}
inline bool is_finite(const vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Orthonormal frame around a unit normal (Duff et al. 2017, "Building an Orthonormal
// Basis, Revisited"): branchless and continuous except at n.z = -1.
struct Frame {
  vec3 s, t, n;

  static Frame from_normal(const vec3& n) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    return {vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x),
            vec3(b, sign + n.y * n.y * a, -n.y), n};
  }
  vec3 to_local(const vec3& v) const { return {glm::dot(v, s), glm::dot(v, t), glm::dot(v, n)}; }
  vec3 to_world(const vec3& v) const { return s * v.x + t * v.y + n * v.z; }
};

// Moves a ray origin off a surface along the geometric normal by a few ulps of the
// coordinates, so the new ray cannot hit the surface it leaves whatever the scale
// (Waechter and Binder, "A Fast and Robust Method for Avoiding Self-Intersection",
// Ray Tracing Gems, 2019). Near zero, where a coordinate's own steps are smaller than the
// error of a point computed from larger ones, the point moves by a fixed amount instead:
// theirs is 1/65536; here it is 1/65536 of `extent` (the largest coordinate of the triangle
// the point lies on), at most 1/65536, since a fixed 1/65536 would be 15% of the height of a
// light 1e-4 above a floor at 1e-4 scale.
constexpr int kRayOffsetSteps = 256;  // a float's steps a ray origin moves away from zero
inline vec3 offset_ray_origin(const vec3& p, const vec3& n, float extent = 1.0f) {
  const float near = fmin_inline(1.0f, extent), origin = near * (1.0f / 32.0f), float_scale = near * (1.0f / 65536.0f);
  vec3 out;
  for (int i = 0; i < 3; ++i) {
    const int of = static_cast<int>(float(kRayOffsetSteps) * n[i]);
    std::int32_t bits;
    std::memcpy(&bits, &p[i], sizeof bits);
    bits += p[i] < 0 ? -of : of;
    float moved;
    std::memcpy(&moved, &bits, sizeof moved);
    out[i] = std::fabs(p[i]) < origin ? p[i] + float_scale * n[i] : moved;
  }
  return out;
}

// Uniform point on the unit disk, concentric mapping (Shirley and Chiu 1997).
inline vec2 sample_concentric_disk(const vec2& u) {
  const vec2 o = 2.0f * u - vec2(1.0f);
  if (o.x == 0.0f && o.y == 0.0f) return vec2(0.0f);
  float r, theta;
  if (std::fabs(o.x) > std::fabs(o.y)) {
    r = o.x;
    theta = (kPi / 4.0f) * (o.y / o.x);
  } else {
    r = o.y;
    theta = (kPi / 2.0f) - (kPi / 4.0f) * (o.x / o.y);
  }
  return r * vec2(std::cos(theta), std::sin(theta));
}

}  // namespace tessera
