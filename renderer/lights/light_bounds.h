// Bounds of a group of lights for many-light sampling (Conty Estevez and Kulla 2018, as pbrt-v4
// writes them): where they are (a box), which way they shine (a cone of axes, and how far past
// an axis light still leaves), and how strong they are. importance() bounds from above what the
// group can deliver to a point, up to one constant for all groups: zero only where no light of
// the group can reach it.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include <xmmintrin.h>

#include "renderer/util/math.h"

namespace tessera {

struct LightBounds {
  vec3 lo{std::numeric_limits<float>::infinity()}, hi{-std::numeric_limits<float>::infinity()};
  vec3 axis{0.0f, 0.0f, 1.0f};  // unit: the cone of the lights' axes is about it
  float cos_spread = 1.0f;  // cos theta_o: how far the axes stray from `axis` (-1: any way)
  float cos_emit = 0.0f;  // cos theta_e: how far from its axis a light still emits
  float power = 0.0f;  // phi: the group's summed strength (luminance of intensity)

  bool empty() const { return !(power > 0.0f); }

  // A bound of the light the group sends to `p` on a surface of normal `n` (either side;
  // n = 0: no surface, as in a medium): zero only where no light of the group can reach it.
  // The one computation is LightBounds4::importance's, in one lane.
  float importance(const vec3& p, const vec3& n) const;

  // The bounds of both groups together.
  static LightBounds merge(const LightBounds& a, const LightBounds& b) {
    if (a.empty()) return b;
    if (b.empty()) return a;
    LightBounds m;
    m.lo = glm::min(a.lo, b.lo);
    m.hi = glm::max(a.hi, b.hi);
    m.power = a.power + b.power;
    m.cos_emit = std::min(a.cos_emit, b.cos_emit);
    merge_cones(a, b, m);
    return m;
  }

 private:
  // The smallest cone holding both cones of axes (pbrt-v4's DirectionCone::Union).
  static void merge_cones(const LightBounds& a, const LightBounds& b, LightBounds& m) {
    const float theta_a = std::acos(std::clamp(a.cos_spread, -1.0f, 1.0f));
    const float theta_b = std::acos(std::clamp(b.cos_spread, -1.0f, 1.0f));
    const float theta_d = std::acos(std::clamp(glm::dot(a.axis, b.axis), -1.0f, 1.0f));
    if (std::min(theta_d + theta_b, kPi) <= theta_a) {  // b inside a
      m.axis = a.axis, m.cos_spread = a.cos_spread;
      return;
    }
    if (std::min(theta_d + theta_a, kPi) <= theta_b) {
      m.axis = b.axis, m.cos_spread = b.cos_spread;
      return;
    }
    const float theta_o = 0.5f * (theta_a + theta_d + theta_b);
    if (theta_o >= kPi) {
      m.axis = a.axis, m.cos_spread = -1.0f;
      return;
    }
    // Rotate a's axis towards b's by theta_o - theta_a about their common normal.
    const float theta_r = theta_o - theta_a;
    const vec3 wr = glm::cross(a.axis, b.axis);
    if (glm::dot(wr, wr) < 1e-12f) {
      m.axis = a.axis, m.cos_spread = -1.0f;
      return;
    }
    const vec3 k = glm::normalize(wr);
    // Rodrigues' rotation of a.axis about k by theta_r.
    const vec3 v = a.axis;
    m.axis = glm::normalize(v * std::cos(theta_r) + glm::cross(k, v) * std::sin(theta_r) +
                            k * glm::dot(k, v) * (1.0f - std::cos(theta_r)));
    m.cos_spread = std::cos(std::min(theta_o + 1e-4f, kPi));  // widened past float rounding
  }
};

// Four groups' bounds side by side (structure of arrays), with what depends on them alone
// worked out once: a tree node's four children, whose importance at a point one pass of SSE
// computes (one square root for the distances, one division, three square roots for the
// angles, for all four). An unused lane has no power: importance 0.
struct LightBounds4 {
  __m128 cx, cy, cz;  // the boxes' centres
  __m128 r2, r;  // the squared radius and radius of each box's bounding sphere
  __m128 ax, ay, az;  // the cones' axes
  __m128 cos_spread, sin_spread, cos_emit;
  __m128 power;  // 0: no group in the lane
  // 1 / the least squared distance importance() divides by: half the box's diagonal (inside
  // it a group is as near as it can be, and a point light a shading point sits on does not
  // make the weight infinite), at least 1e-12.
  __m128 inv_d2_floor;

  LightBounds4();
  void set(int lane, const LightBounds& b);  // an empty b leaves the lane unused

  // Each group's bound of the light it sends to `p` on a surface of normal `n` (either side;
  // n = 0: no surface, as in a medium), pbrt-v4's LightBounds::Importance: power x the cosine
  // of the smallest angle between a light's axis and the direction to p (the axis' spread and
  // the box's angle taken off) / the squared distance, x the largest incident cosine over the
  // box; 0 past the emission angle.
  void importance(const vec3& p, const vec3& n, float out[4]) const {
    const __m128 zero = _mm_setzero_ps(), one = _mm_set1_ps(1.0f);
    auto select = [](__m128 mask, __m128 a, __m128 b) { return _mm_or_ps(_mm_and_ps(mask, a), _mm_andnot_ps(mask, b)); };
    auto safe_sqrt = [&](__m128 x) { return _mm_sqrt_ps(_mm_max_ps(x, zero)); };
    // cos(a - b) and sin(a - b), as 1 and 0 where b >= a (the difference clamped at 0).
    auto cos_minus = [&](__m128 sin_a, __m128 cos_a, __m128 sin_b, __m128 cos_b) {
      return select(_mm_cmpgt_ps(cos_a, cos_b), one, _mm_add_ps(_mm_mul_ps(cos_a, cos_b), _mm_mul_ps(sin_a, sin_b)));
    };
    auto sin_minus = [&](__m128 sin_a, __m128 cos_a, __m128 sin_b, __m128 cos_b) {
      return select(_mm_cmpgt_ps(cos_a, cos_b), zero, _mm_sub_ps(_mm_mul_ps(sin_a, cos_b), _mm_mul_ps(cos_a, sin_b)));
    };
    const __m128 wx = _mm_sub_ps(_mm_set1_ps(p.x), cx), wy = _mm_sub_ps(_mm_set1_ps(p.y), cy),
                 wz = _mm_sub_ps(_mm_set1_ps(p.z), cz);
    const __m128 dist2 = _mm_add_ps(_mm_add_ps(_mm_mul_ps(wx, wx), _mm_mul_ps(wy, wy)), _mm_mul_ps(wz, wz));
    const __m128 away = _mm_cmpgt_ps(dist2, zero);
    const __m128 inv_len = _mm_and_ps(away, _mm_div_ps(one, _mm_sqrt_ps(dist2)));
    const __m128 inv_d2 = _mm_min_ps(_mm_mul_ps(inv_len, inv_len), inv_d2_floor);  // 1 / max(d^2, floor)
    // The direction from the centre to p (the axis from the centre itself).
    const __m128 ux = select(away, _mm_mul_ps(wx, inv_len), ax), uy = select(away, _mm_mul_ps(wy, inv_len), ay),
                 uz = select(away, _mm_mul_ps(wz, inv_len), az);
    const __m128 cos_w = _mm_add_ps(_mm_add_ps(_mm_mul_ps(ax, ux), _mm_mul_ps(ay, uy)), _mm_mul_ps(az, uz));
    const __m128 sin_w = safe_sqrt(_mm_sub_ps(one, _mm_mul_ps(cos_w, cos_w)));
    // The box as seen from p: its bounding sphere's half-angle (sin = r / d), every direction
    // from inside it.
    const __m128 inside = _mm_cmple_ps(dist2, r2);
    const __m128 sin_b = _mm_andnot_ps(inside, _mm_min_ps(_mm_mul_ps(r, inv_len), one));
    const __m128 cos_b = select(inside, _mm_set1_ps(-1.0f), safe_sqrt(_mm_sub_ps(one, _mm_mul_ps(sin_b, sin_b))));
    const __m128 cos_x = cos_minus(sin_w, cos_w, sin_spread, cos_spread);
    const __m128 sin_x = sin_minus(sin_w, cos_w, sin_spread, cos_spread);
    const __m128 cos_theta = cos_minus(sin_x, cos_x, sin_b, cos_b);
    __m128 importance = _mm_mul_ps(_mm_mul_ps(power, cos_theta), inv_d2);
    if (n != vec3(0.0f)) {  // the incident cosine, at its largest over the box
      const __m128 dot = _mm_add_ps(_mm_add_ps(_mm_mul_ps(ux, _mm_set1_ps(n.x)), _mm_mul_ps(uy, _mm_set1_ps(n.y))),
                                    _mm_mul_ps(uz, _mm_set1_ps(n.z)));
      const __m128 cos_i = _mm_andnot_ps(_mm_set1_ps(-0.0f), dot);
      const __m128 sin_i = safe_sqrt(_mm_sub_ps(one, _mm_mul_ps(cos_i, cos_i)));
      importance = _mm_mul_ps(importance, cos_minus(sin_i, cos_i, sin_b, cos_b));
    }
    // 0 past the emission angle, in an unused lane, and for NaN; at most the largest float.
    const __m128 lit = _mm_and_ps(_mm_cmpgt_ps(cos_theta, cos_emit), _mm_cmpgt_ps(power, zero));
    importance = _mm_and_ps(lit, _mm_min_ps(_mm_max_ps(importance, zero), _mm_set1_ps(std::numeric_limits<float>::max())));
    _mm_storeu_ps(out, importance);
  }
};

inline LightBounds4::LightBounds4() {
  const __m128 zero = _mm_setzero_ps();
  cx = cy = cz = r2 = r = ax = ay = az = cos_spread = sin_spread = cos_emit = power = inv_d2_floor = zero;
}

inline void LightBounds4::set(int lane, const LightBounds& b) {
  if (b.empty()) return;
  auto put = [lane](__m128& v, float x) {
    alignas(16) float f[4];
    _mm_store_ps(f, v);
    f[lane] = x;
    v = _mm_load_ps(f);
  };
  const vec3 diagonal = b.hi - b.lo, centre = 0.5f * (b.lo + b.hi);
  const float radius2 = 0.25f * glm::dot(diagonal, diagonal);
  put(cx, centre.x), put(cy, centre.y), put(cz, centre.z);
  put(r2, radius2), put(r, std::sqrt(radius2));
  put(ax, b.axis.x), put(ay, b.axis.y), put(az, b.axis.z);
  put(cos_spread, b.cos_spread);
  put(sin_spread, std::sqrt(std::max(1.0f - b.cos_spread * b.cos_spread, 0.0f)));
  put(cos_emit, b.cos_emit);
  put(power, b.power);
  put(inv_d2_floor, 1.0f / std::max(0.5f * glm::length(diagonal), 1e-12f));
}

inline float LightBounds::importance(const vec3& p, const vec3& n) const {
  LightBounds4 one;
  one.set(0, *this);
  float out[4];
  one.importance(p, n, out);
  return out[0];
}

}  // namespace tessera
