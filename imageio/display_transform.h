// From scene-linear RGB to what a display shows, for 8-bit previews (PNG, JPEG, ...): an
// OpenColorIO view. Built in: `filmic`, a log2 shaper around middle grey, a filmic tone
// curve (Narkowicz's fit of the ACES RRT+ODT, 2015) that rolls highlights off instead of
// clipping them, then the sRGB encoding; `standard`, the sRGB encoding of the clipped value.
// A studio's own OCIO config replaces them: its scene_linear role to one of its displays
// and views. EXR output never passes through here: it stays scene-linear.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace tessera {

enum class ViewTransform : std::uint8_t { filmic, standard };

const char* view_transform_name(ViewTransform view);
ViewTransform parse_view_transform(const std::string& name);  // throws std::invalid_argument
const std::vector<std::string>& view_transform_names();

struct DisplayParams {
  ViewTransform view = ViewTransform::filmic;
  // (The {} keep DisplayParams{view} free of -Wmissing-field-initializers.)
  std::string ocio_config{};  // an OCIO config file: its display and view instead of `view`
  std::string ocio_display{}, ocio_view{};  // empty: the config's default display, its default view
};

// A display or view the config does not have, an unreadable config: the message names the
// file and what it has.
struct DisplayTransformError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The filmic view's tone curve, scene-linear to display-linear (before the sRGB encoding).
float filmic_curve(float x);

// Checks that the transform can be built (the config read, the display and view found).
void check_display_transform(const DisplayParams& params);

// `rgb` (3 floats a pixel) times 2^exposure through the view: display values, clamped to
// [0, 1], as 8-bit codes.
std::vector<std::uint8_t> to_display_rgb8(const std::vector<float>& rgb, float exposure, const DisplayParams& params);

}  // namespace tessera
