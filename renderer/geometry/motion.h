// Motion while the shutter is open. The scene gives what moves at `steps` motion steps
// evenly spaced over the shutter (step 0 at its opening, the last at its closing); the
// renderer reads them at a time in [0, 1), the fraction of the shutter. Between two steps,
// vertices move linearly, as Embree intersects them, and transforms are interpolated by
// parts (translation and scale/shear linearly, the rotation by slerp), as Embree's quaternion
// motion blur places instances: a turning wheel keeps its size, where interpolating the
// matrices would shrink it halfway.
#pragma once

#include <algorithm>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "renderer/util/math.h"
#include "renderer/description/scene.h"

namespace tessera {

// Where a time falls: between step `step` and step + 1, `fraction` of the way.
struct MotionSegment {
  int step = 0;
  float fraction = 0.0f;
};

// Embree's rule (getTimeSegment, time range [0, 1]) to the bit, so that shading reads the
// surface exactly where the ray met it. steps >= 2.
inline MotionSegment motion_segment(float time, int steps) {
  const float segments = static_cast<float>(steps - 1);
  const float scaled = time * segments;
  const float index = std::clamp(std::floor(scaled), 0.0f, segments - 1.0f);
  return {static_cast<int>(index), scaled - index};
}

template <typename T>
T lerp_step(const T& a, const T& b, float fraction) {
  return (1.0f - fraction) * a + fraction * b;
}

// One vertex attribute at a time: `step0` is step 0, `later` steps 1 .. steps - 1 (the
// layout of TriangleMesh's motion arrays).
template <typename T>
T attribute_at(const MeshArray<T>& step0, const std::vector<MeshArray<T>>& later, std::uint32_t vertex,
               MotionSegment seg) {
  const MeshArray<T>& a = seg.step == 0 ? step0 : later[seg.step - 1];
  return lerp_step(a[vertex], later[seg.step][vertex], seg.fraction);
}

// An affine transform in parts: translate(translation) * rotation * upper, `upper` upper
// triangular (scale on the diagonal, shear above it), Embree's RTCQuaternionDecomposition.
struct AffineParts {
  vec3 translation{0.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
  glm::mat3 upper{1.0f};
};

// Gram-Schmidt on the columns (QR): exact for glTF's T * R * S. A mirroring transform keeps a
// proper rotation and takes the mirror as a negative scale in z.
AffineParts decompose(const glm::mat4& m);
glm::mat4 compose(const AffineParts& parts);
// The rotation by slerp the short way, the rest linearly.
AffineParts interpolate(const AffineParts& a, const AffineParts& b, float fraction);

// A transform given at motion steps (each decomposed once), read at any time.
class MotionTransform {
 public:
  MotionTransform() = default;
  explicit MotionTransform(const std::vector<glm::mat4>& steps);
  bool empty() const { return steps_.empty(); }
  glm::mat4 at(float time) const;
  const std::vector<AffineParts>& steps() const { return steps_; }

 private:
  std::vector<AffineParts> steps_;
};

}  // namespace tessera
