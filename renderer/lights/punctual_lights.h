// KHR_lights_punctual lights for next-event estimation. Units as the specification gives
// them, taken one to one as scene radiometry: a point light of I candela delivers
// irradiance I / d^2 at distance d, a directional light of E lux delivers E.
#pragma once

#include <limits>

#include "renderer/util/math.h"
#include "renderer/description/scene.h"

namespace tessera {

struct LightSample {
  vec3 wi{0.0f};  // unit direction from the shading point to the light
  float distance = std::numeric_limits<float>::infinity();
  vec3 irradiance{0.0f};  // on a surface facing the light (before the cosine)
};

// Where a light is: its position and the way it shines (world space).
struct LightPlacement {
  vec3 position{0.0f}, direction{0.0f, 0.0f, -1.0f};
};

// The placement a light-to-world transform gives: its origin, and its -Z.
inline LightPlacement light_placement(const glm::mat4& light_to_world) {
  return {vec3(light_to_world[3]), glm::normalize(-vec3(light_to_world[2]))};
}

inline bool sample_punctual_light(const PunctualLight& light, const LightPlacement& at, const vec3& p, LightSample& s) {
  const vec3 radiant = light.color * light.intensity;
  if (light.type == PunctualLight::Type::Directional) {
    s.wi = -at.direction;
    s.distance = std::numeric_limits<float>::infinity();
    s.irradiance = radiant;
    return true;
  }
  const vec3 to_light = at.position - p;
  const float d2 = glm::dot(to_light, to_light);
  if (!(d2 > 0.0f)) return false;
  s.distance = std::sqrt(d2);
  s.wi = to_light / s.distance;
  float falloff = 1.0f / d2;
  if (light.range > 0.0f) {  // the specification's recommended smooth window
    const float r = s.distance / light.range;
    falloff *= glm::clamp(1.0f - r * r * r * r, 0.0f, 1.0f);
  }
  if (light.type == PunctualLight::Type::Spot) {
    const float cos_outer = std::cos(light.outer_cone_angle), cos_inner = std::cos(light.inner_cone_angle);
    const float scale = 1.0f / fmax_inline(0.001f, cos_inner - cos_outer);
    const float t = glm::clamp((glm::dot(-s.wi, at.direction) - cos_outer) * scale, 0.0f, 1.0f);
    falloff *= t * t;
  }
  s.irradiance = radiant * falloff;
  return falloff > 0.0f;
}

}  // namespace tessera
