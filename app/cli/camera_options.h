// A camera from the command line: --look-at EYE,TARGET,UP, --camera-position X,Y,Z with
// --camera-target X,Y,Z (default: the scene's centre; up +Y), or --orbit around the scene's
// centre. Its lens is the automatic camera's; --fov replaces it as for any perspective camera.
#pragma once

#include <optional>

#include "app/cli/options.h"
#include "renderer/util/math.h"

namespace tessera {

struct LookAt {
  vec3 eye{0.0f}, target{0.0f}, up{0.0f, 1.0f, 0.0f};
};

struct Orbit {
  float azimuth = 0.0f, elevation = 0.0f;  // degrees
  float distance = 0.0f;  // 0: the automatic camera's
};

// --orbit AZIMUTH,ELEVATION[,DISTANCE]; nothing when not given. Throws UsageError for
// malformed numbers, an elevation not strictly between -90 and 90 (the view would be along
// up) or a distance that is not positive.
std::optional<Orbit> command_line_orbit(const RenderOptions& o);

// Nothing when neither option is given. Throws UsageError for malformed numbers or a
// degenerate view: the eye at the target, or up along the view direction.
std::optional<LookAt> command_line_look_at(const RenderOptions& o, const vec3& scene_center);

}  // namespace tessera
