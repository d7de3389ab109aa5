#pragma once

#include <limits>

#include "renderer/util/math.h"

namespace tessera {

struct Ray {
  vec3 origin;
  vec3 direction;  // unit length
  float tmin = 0.0f;
  float tmax = std::numeric_limits<float>::infinity();
  // When the ray looks, as a fraction of the shutter interval in [0, 1) (renderer/geometry/motion.h):
  // every ray of a path (camera, bounces, shadow rays) sees the scene at the path's time.
  float time = 0.0f;
};

}  // namespace tessera
