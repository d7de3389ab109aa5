// The `--background auto` rule: black when the scene's own lights can light it, else white
// (1,1,1), so that a model made to be lit by an environment is not rendered in the dark.
// Its own lights can light it when it places a punctual light, or when its emitters (triangles
// emitting without an emissive texture) send out at least kAutoBlackShare of the power a white
// background would bring onto its bounding box. A small bulb on a large unlit body does not.
#pragma once

#include <string>

#include "renderer/description/scene.h"

namespace tessera {

inline constexpr double kAutoBlackShare = 0.01;

struct AutoBackground {
  bool black = false;
  std::string why;  // "1 punctual light", "emitters give 9.2% of the power a white background would"
};

AutoBackground choose_auto_background(const SceneDescription& scene);

// What a uniform background of radiance 1 brings onto the scene's bounding box: pi x its area.
double white_background_power(const SceneDescription& scene);
// The power, in luminance, of the emitters without an emissive texture: pi x L x area (x 2 when
// double-sided), the areas as placed in the world.
double untextured_emitter_power(const SceneDescription& scene);

}  // namespace tessera
