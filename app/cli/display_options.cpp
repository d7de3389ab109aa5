#include "app/cli/display_options.h"

#include "app/cli/exit_codes.h"

namespace tessera {

void add_display_options(CLI::App* cmd, DisplayOptions& o, const std::string& group) {
  cmd->add_option("--exposure", o.exposure, "Exposure in stops applied to non-EXR outputs (display formats: before the view transform; .hdr/.tif/.pfm: linear)")
      ->check(CLI::Range(-64.0f, 64.0f))->capture_default_str()
      ->group(group);
  cmd->add_option("--view-transform", o.view_transform,
                  "Display formats (PNG, JPEG, ...): filmic (highlights roll off, through OpenColorIO) or standard "
                  "(the clipped value, sRGB encoded). The EXR stays scene-linear")
      ->check(CLI::IsMember(view_transform_names()))->capture_default_str()
      ->group(group);
  cmd->add_option("--ocio-config", o.ocio_config,
                  "Display formats: an OpenColorIO config whose view to use instead (from its scene_linear role)")
      ->check(CLI::ExistingFile)
      ->group(group);
  cmd->add_option("--ocio-display", o.ocio_display, "With --ocio-config: the display [default: the config's]")
      ->group(group);
  cmd->add_option("--ocio-view", o.ocio_view, "With --ocio-config: the view [default: the display's default view]")
      ->group(group);
}

DisplayParams plan_display(const DisplayOptions& o) {
  DisplayParams d{parse_view_transform(o.view_transform), o.ocio_config, o.ocio_display, o.ocio_view};
  if (o.ocio_config.empty() && (!o.ocio_display.empty() || !o.ocio_view.empty()))
    throw UsageError("--ocio-display and --ocio-view choose within --ocio-config, which is not given");
  try {
    check_display_transform(d);
  } catch (const DisplayTransformError& e) {
    throw UsageError(e.what());
  }
  return d;
}

}  // namespace tessera
