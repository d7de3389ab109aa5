#pragma once

#include <limits>

#include "renderer/math.h"

namespace tessera {

struct Ray {
  vec3 origin;
  vec3 direction;  // unit length
  float tmin = 0.0f;
  float tmax = std::numeric_limits<float>::infinity();
};

}  // namespace tessera
