// Bounds of a group of lights for many-light sampling (Conty Estevez and Kulla 2018, as pbrt-v4
// writes them): where they are (a box), which way they shine (a cone of axes, and how far past
// an axis light still leaves), and how strong they are. importance() bounds from above what the
// group can deliver to a point, up to one constant for all groups: zero only where no light of
// the group can reach it.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "renderer/util/math.h"

namespace tessera {

struct LightBounds {
  vec3 lo{std::numeric_limits<float>::infinity()}, hi{-std::numeric_limits<float>::infinity()};
  vec3 axis{0.0f, 0.0f, 1.0f};  // unit: the cone of the lights' axes is about it
  float cos_spread = 1.0f;  // cos theta_o: how far the axes stray from `axis` (-1: any way)
  float cos_emit = 0.0f;  // cos theta_e: how far from its axis a light still emits
  float power = 0.0f;  // phi: the group's summed strength (luminance of intensity)

  bool empty() const { return !(power > 0.0f); }

  // What importance() reads, with what depends on the bounds alone worked out once: the form
  // a tree keeps in its nodes (one cache line with the node's links), whose walk evaluates two
  // of them per level. importance() takes one square root for the distance, one division and
  // three square roots for the angles.
  struct Prepared {
    vec3 centre{0.0f};
    float r2 = 0.0f;  // the squared radius of the box's bounding sphere
    vec3 axis{0.0f, 0.0f, 1.0f};
    float r = 0.0f;  // that radius
    float cos_spread = 1.0f, sin_spread = 0.0f, cos_emit = 0.0f;
    float power = 0.0f;  // 0: empty
    // 1 / the least squared distance importance() divides by: half the box's diagonal (inside
    // it a group is as near as it can be, and a point light a shading point sits on does not
    // make the weight infinite), at least 1e-12.
    float inv_d2_floor = 0.0f;

    // A bound of the light the group sends to `p` on a surface of normal `n` (either side;
    // n = 0: no surface, as in a medium).
    float importance(const vec3& p, const vec3& n) const {
      if (!(power > 0.0f)) return 0.0f;
      const vec3 wi = p - centre;
      const float dist2 = glm::dot(wi, wi);
      const float inv_len = dist2 > 0.0f ? 1.0f / std::sqrt(dist2) : 0.0f;
      const float inv_d2 = std::min(inv_len * inv_len, inv_d2_floor);  // 1 / max(d^2, floor)
      // cos and sin of the angles of the bound: the axis to the point, the box as seen from it
      // (its bounding sphere's: sin = r / d; every direction from inside it).
      const vec3 w = dist2 > 0.0f ? wi * inv_len : axis;
      const float cos_w = glm::dot(axis, w), sin_w = safe_sqrt(1.0f - cos_w * cos_w);
      const bool inside = dist2 <= r2;
      const float sin_b = inside ? 0.0f : std::min(r * inv_len, 1.0f);
      const float cos_b = inside ? -1.0f : safe_sqrt(1.0f - sin_b * sin_b);
      // The smallest angle between a light's axis and the direction to the point: theta_w
      // less the axes' spread, less the box's angle (each clamped at 0).
      const float cos_x = cos_minus(sin_w, cos_w, sin_spread, cos_spread), sin_x = sin_minus(sin_w, cos_w, sin_spread, cos_spread);
      const float cos_theta = cos_minus(sin_x, cos_x, sin_b, cos_b);
      if (cos_theta <= cos_emit) return 0.0f;
      float importance = power * cos_theta * inv_d2;
      if (n != vec3(0.0f)) {  // the incident cosine, at its largest over the box
        const float cos_i = std::fabs(glm::dot(w, n)), sin_i = safe_sqrt(1.0f - cos_i * cos_i);
        importance *= cos_minus(sin_i, cos_i, sin_b, cos_b);
      }
      return std::min(std::max(importance, 0.0f), std::numeric_limits<float>::max());
    }
  };

  Prepared prepared() const {
    if (empty()) return {};
    const vec3 diagonal = hi - lo;
    Prepared q;
    q.centre = 0.5f * (lo + hi);
    q.r2 = 0.25f * glm::dot(diagonal, diagonal);
    q.r = std::sqrt(q.r2);
    q.axis = axis;
    q.inv_d2_floor = 1.0f / std::max(0.5f * glm::length(diagonal), 1e-12f);
    q.cos_spread = cos_spread;
    q.sin_spread = safe_sqrt(1.0f - cos_spread * cos_spread);
    q.cos_emit = cos_emit;
    q.power = power;
    return q;
  }

  // A bound of the light the group sends to `p` on a surface of normal `n` (either side;
  // n = 0: no surface, as in a medium): zero only where no light of the group can reach it.
  float importance(const vec3& p, const vec3& n) const { return prepared().importance(p, n); }

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
  static float safe_sqrt(float x) { return std::sqrt(std::max(x, 0.0f)); }
  // cos(a - b) and sin(a - b), as 1 and 0 where b >= a (the difference clamped at 0).
  static float cos_minus(float sin_a, float cos_a, float sin_b, float cos_b) {
    return cos_a > cos_b ? 1.0f : cos_a * cos_b + sin_a * sin_b;
  }
  static float sin_minus(float sin_a, float cos_a, float sin_b, float cos_b) {
    return cos_a > cos_b ? 0.0f : sin_a * cos_b - cos_a * sin_b;
  }
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

}  // namespace tessera
