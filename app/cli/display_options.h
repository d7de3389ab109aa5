// How a command's display-referred outputs look (--exposure, --view-transform, --ocio-*):
// `tessera render`'s non-EXR outputs and previews, `tessera denoise`'s preview. One set of
// options, added and checked the same way for both.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "imageio/display_transform.h"

namespace tessera {

struct DisplayOptions {
  float exposure = 0.0f;  // stops, before the view
  std::string view_transform = "filmic";  // display formats: the built-in view
  std::string ocio_config, ocio_display, ocio_view;  // a studio's OCIO config and its view
};

// Adds the options to `cmd`, in `group` (its --help heading; CLI11 hides an empty one).
void add_display_options(CLI::App* cmd, DisplayOptions& o, const std::string& group);

// The view transform, built once so that a bad config fails before any work. Throws
// UsageError naming the option or the config's problem.
DisplayParams plan_display(const DisplayOptions& o);

}  // namespace tessera
