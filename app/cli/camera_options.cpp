#include "app/cli/camera_options.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

#include <fmt/format.h>

#include "app/cli/exit_codes.h"

namespace tessera {

namespace {

// `count` comma-separated finite numbers, else UsageError naming the option.
std::vector<float> parse_numbers(const char* option, const std::string& text, int count, const char* form) {
  std::vector<float> values;
  const char* p = text.c_str();
  for (;;) {
    char* end = nullptr;
    const double v = std::strtod(p, &end);
    if (end == p || !std::isfinite(v)) break;
    values.push_back(static_cast<float>(v));
    p = end;
    if (*p != ',') break;
    ++p;
  }
  if (*p != '\0' || static_cast<int>(values.size()) != count)
    throw UsageError(fmt::format("{} {}: expected {} ({} numbers separated by commas)", option, text, form, count));
  return values;
}

vec3 parse_point(const char* option, const std::string& text) {
  const std::vector<float> v = parse_numbers(option, text, 3, "X,Y,Z");
  return {v[0], v[1], v[2]};
}

}  // namespace

std::optional<Orbit> command_line_orbit(const RenderOptions& o) {
  if (o.orbit.empty()) return std::nullopt;
  const char* option = "--orbit";
  const bool with_distance = std::count(o.orbit.begin(), o.orbit.end(), ',') == 2;
  const std::vector<float> v =
      parse_numbers(option, o.orbit, with_distance ? 3 : 2, with_distance ? "AZIMUTH,ELEVATION,DISTANCE" : "AZIMUTH,ELEVATION");
  const Orbit orbit{v[0], v[1], with_distance ? v[2] : 0.0f};
  if (!(std::abs(orbit.elevation) < 90.0f))
    throw UsageError(fmt::format("{} {}: the elevation must lie strictly between -90 and 90 degrees (at the poles "
                                 "the view is along up)", option, o.orbit));
  if (with_distance && !(orbit.distance > 0.0f))
    throw UsageError(fmt::format("{} {}: the distance must be positive", option, o.orbit));
  return orbit;
}

std::optional<LookAt> command_line_look_at(const RenderOptions& o, const vec3& scene_center) {
  LookAt view;
  const char* option = "--look-at";
  if (!o.look_at.empty()) {
    const std::vector<float> v = parse_numbers(option, o.look_at, 9, "EYE,TARGET,UP");
    view = {{v[0], v[1], v[2]}, {v[3], v[4], v[5]}, {v[6], v[7], v[8]}};
  } else if (!o.camera_position.empty()) {
    option = "--camera-position";
    view.eye = parse_point(option, o.camera_position);
    view.target = o.camera_target.empty() ? scene_center : parse_point("--camera-target", o.camera_target);
  } else {
    return std::nullopt;
  }
  const vec3 view_direction = view.target - view.eye;
  const float distance = glm::length(view_direction);
  if (!(distance > 1e-6f * std::max(1.0f, glm::length(view.eye))))
    throw UsageError(fmt::format("{}: the eye and the target are the same point, so there is no view direction", option));
  if (!(glm::length(glm::cross(view_direction / distance, view.up)) > 1e-4f * glm::length(view.up)))
    throw UsageError(fmt::format("{}: up ({}, {}, {}) is zero or along the view direction; give another up",
                                 option, view.up.x, view.up.y, view.up.z));
  return view;
}

}  // namespace tessera
