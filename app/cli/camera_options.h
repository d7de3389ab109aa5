// A camera from the command line: --look-at EYE,TARGET,UP, or --camera-position X,Y,Z with
// --camera-target X,Y,Z (default: the scene's centre; up +Y). Its lens is the automatic
// camera's; --fov replaces it as for any perspective camera.
#pragma once

#include <optional>

#include "app/cli/options.h"
#include "renderer/util/math.h"

namespace tessera {

struct LookAt {
  vec3 eye{0.0f}, target{0.0f}, up{0.0f, 1.0f, 0.0f};
};

// Nothing when neither option is given. Throws UsageError for malformed numbers or a
// degenerate view: the eye at the target, or up along the view direction.
std::optional<LookAt> command_line_look_at(const RenderOptions& o, const vec3& scene_center);

}  // namespace tessera
