#include "renderer/geometry/motion.h"

namespace tessera {

AffineParts decompose(const glm::mat4& m) {
  // In double: the parts of a float matrix come out to float precision.
  const glm::dmat3 a = glm::dmat3(glm::mat3(m));
  glm::dmat3 q(1.0), u(0.0);  // a = q * u, q orthonormal, u upper triangular
  for (int i = 0; i < 3; ++i) {
    glm::dvec3 rest = a[i];
    for (int j = 0; j < i; ++j) {
      u[i][j] = glm::dot(q[j], a[i]);
      rest -= u[i][j] * q[j];
    }
    const double len = glm::length(rest);
    u[i][i] = len;
    if (len > 1e-300 * (1.0 + glm::length(a[i]))) {
      q[i] = rest / len;
    } else {  // a flattened transform: any direction completes the basis, its scale is 0
      if (i == 0) q[0] = glm::dvec3(1, 0, 0);
      else if (i == 1) q[1] = glm::normalize(std::fabs(q[0].x) < 0.9 ? glm::cross(q[0], glm::dvec3(1, 0, 0)) : glm::cross(q[0], glm::dvec3(0, 1, 0)));
      else q[2] = glm::cross(q[0], q[1]);
    }
  }
  if (glm::determinant(q) < 0.0) {  // a mirror: a proper rotation and a negative z scale
    q[2] = -q[2];
    u[2][2] = -u[2][2];
  }
  AffineParts p;
  p.translation = vec3(m[3]);
  p.rotation = glm::normalize(glm::quat_cast(glm::mat3(q)));
  p.upper = glm::mat3(u);
  return p;
}

glm::mat4 compose(const AffineParts& parts) {
  glm::mat4 m(glm::mat3_cast(parts.rotation) * parts.upper);
  m[3] = vec4(parts.translation, 1.0f);
  return m;
}

AffineParts interpolate(const AffineParts& a, const AffineParts& b, float fraction) {
  AffineParts p;
  p.translation = lerp_step(a.translation, b.translation, fraction);
  p.rotation = glm::normalize(glm::slerp(a.rotation, b.rotation, fraction));
  p.upper = lerp_step(a.upper, b.upper, fraction);
  return p;
}

MotionTransform::MotionTransform(const std::vector<glm::mat4>& steps) {
  steps_.reserve(steps.size());
  for (const glm::mat4& m : steps) steps_.push_back(decompose(m));
}

glm::mat4 MotionTransform::at(float time) const {
  if (steps_.size() == 1) return compose(steps_[0]);
  const MotionSegment seg = motion_segment(time, static_cast<int>(steps_.size()));
  return compose(interpolate(steps_[seg.step], steps_[seg.step + 1], seg.fraction));
}

}  // namespace tessera
