#include "app/commands/option_rules.h"

#include <algorithm>
#include <filesystem>
#include <limits>

#include <fmt/format.h>

#include "app/cli/exit_codes.h"
#include "app/frame/frame_pipeline.h"
#include "renderer/sampling/adaptive_sampling.h"
#include "imageio/image_output.h"

namespace tessera {

namespace {

// Whether two paths name one file, which need not exist yet ("a.exr" and "./a.exr").
bool same_file(const std::string& a, const std::string& b) {
  auto normal = [](const std::string& p) {
    return std::filesystem::weakly_canonical(std::filesystem::absolute(p)).lexically_normal();
  };
  return normal(a) == normal(b);
}

// The image files a render writes: -o (or its default) and --preview.
std::vector<std::string> image_outputs(const RenderOptions& o) {
  std::vector<std::string> files{frame_output_path(o)};
  if (!o.preview.empty()) files.push_back(o.preview);
  return files;
}

template <typename Predicate>
bool any_output(const RenderOptions& o, Predicate p) {
  for (const std::string& f : image_outputs(o))
    if (p(f)) return true;
  return false;
}

// Options that only shape the written image or how it is rendered in parallel: nothing of
// theirs happens when --pixel traces one pixel and writes nothing.
const char* const kNotWithPixel[] = {"--output", "--preview", "--aov", "--half", "--owner", "--comments",
                                     "--film-transparent", "--exposure", "--view-transform",
                                     "--ocio-config", "--ocio-display", "--ocio-view", "--denoise",
                                     "--time-limit", "--checkpoint", "--noise-threshold", "--min-spp",
                                     "--threads", "--tile-size", "--scheduler", "--tile-order",
                                     "--rank-scheduler", "--stats-json", "--trace", "--heatmap",
                                     "--skip-existing"};

void pixel_warnings(const RenderOptions& o, std::vector<std::string>& out) {
  for (const char* name : kNotWithPixel)
    if (given(o, name)) out.push_back(fmt::format("{}: has no effect with --pixel, which writes no image", name));
}

}  // namespace

bool given(const RenderOptions& o, const char* name) {
  return std::find(o.given.begin(), o.given.end(), name) != o.given.end();
}

void apply_quick_preset(RenderOptions& o) {
  if (!o.quick) return;
  if (!given(o, "--resolution-scale")) o.resolution_scale = 0.25f;
  if (!given(o, "--spp")) o.spp = 4;
  if (!given(o, "--max-bounces")) o.max_bounces = 4;
}

void check_option_conflicts(const RenderOptions& o) {
  if (given(o, "--view-transform") && given(o, "--ocio-config"))
    throw UsageError("--view-transform and --ocio-config both choose the view of display formats: give one");
  if (!o.preview.empty() && same_file(o.preview, frame_output_path(o)))
    throw UsageError(fmt::format("--preview {}: is the -o file too; give another name", o.preview));
  if (!o.pixel.empty())
    for (const char* name : {"--frames", "--resume", "--crop"})
      if (given(o, name)) throw UsageError(fmt::format("--pixel traces one pixel of one frame: {} cannot go with it", name));
}

std::vector<std::string> ignored_option_warnings(const RenderOptions& o, bool distributed) {
  std::vector<std::string> out;
  auto warn = [&](const char* name, bool no_effect, const std::string& why) {
    if (given(o, name) && no_effect) out.push_back(fmt::format("{}: {}", name, why));
  };
  if (!o.pixel.empty()) {
    pixel_warnings(o, out);
  } else {
    const bool exr = any_output(o, is_exr_path);
    const bool linear_only = !any_output(o, [](const std::string& f) { return !is_exr_path(f); });
    const bool display = any_output(o, is_display_format_path);
    warn("--aov", !exr, "layers need an EXR output (-o or --preview FILE.exr); none is written");
    warn("--half", !exr, "half floats are an EXR option; no EXR is written");
    warn("--owner", !exr, "is an EXR header attribute; no EXR is written");
    warn("--comments", !exr, "is an EXR header attribute; no EXR is written");
    warn("--exposure", linear_only, "applies to non-EXR outputs only (the EXR stays scene-linear); add --preview FILE.png");
    for (const char* view : {"--view-transform", "--ocio-config", "--ocio-display", "--ocio-view"})
      warn(view, !display, "applies to display formats (PNG, JPEG, ...) only; none is written");
    warn("--rank-scheduler", !distributed, "applies only under mpirun with more than one rank");
    warn("--skip-existing", o.frames.empty() && o.frame < 0, "applies only with --frames or --frame");
    const int first = adaptive_min_spp({o.noise_threshold, o.min_spp}, std::numeric_limits<int>::max());
    warn("--noise-threshold", o.noise_threshold > 0.0f && first >= o.spp,
         fmt::format("no pixel can stop early: each takes {} samples (its min spp) before it may, and --spp is {}",
                     first, o.spp));
  }
  warn("--focus-distance", o.aperture <= 0.0f, "has no effect without --aperture (a pinhole camera is in focus everywhere)");
  warn("--envmap-scale", o.envmap.empty(), "has no effect without --envmap");
  warn("--envmap-rotate", o.envmap.empty(), "has no effect without --envmap");
  warn("--background", !o.envmap.empty(), "ignored with --envmap (the environment image is the background)");
  warn("--fps", o.frame < 0 && o.frames.empty() && o.shutter.empty(), "only converts --frame, --frames and --shutter, none of which is given");
  warn("--motion-steps", o.shutter.empty(), "has no effect without --shutter (no motion blur)");
  return out;
}

}  // namespace tessera
