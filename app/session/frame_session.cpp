#include "app/session/frame_session.h"

#include <CLI/CLI.hpp>

#include "app/cli/command_line.h"
#include "app/cli/command_parser.h"
#include "app/cli/exit_codes.h"
#include "app/commands/commands.h"
#include "app/commands/option_rules.h"
#include "app/commands/render_job.h"
#include "renderer/profile/render_stats.h"

namespace tessera {

namespace {

// The options that name files to write or continue, or trace one pixel: not for a render whose
// layers stay in memory.
void refuse_file_options(const RenderOptions& o) {
  for (const char* name : {"--output", "--preview", "--resume", "--checkpoint", "--frames", "--skip-existing",
                           "--stats-json", "--trace", "--heatmap", "--heatmap-by", "--pixel"})
    if (given(o, name)) throw UsageError(std::string(name) + ": a render in memory writes and reads no file");
}

// The render command's options from `arguments`, as `tessera render PATH ARGUMENTS...` reads them.
RenderOptions parse_render_options(const std::string& path, const std::vector<std::string>& arguments) {
  RenderOptions o;
  CLI::App app{"tessera", "tessera"};
  add_render_command(app, o);
  std::vector<std::string> args{"render", path};
  args.insert(args.end(), arguments.begin(), arguments.end());
  parse_arguments(app, args);
  std::vector<const char*> argv{"tessera"};
  for (const std::string& a : args) argv.push_back(a.c_str());
  o.command_line = shell_command_line(static_cast<int>(argv.size()), argv.data());  // how to render it again
  refuse_file_options(o);
  apply_quick_preset(o);
  check_option_conflicts(o);
  check_value_syntax(o);
  return o;
}

}  // namespace

FrameSession::FrameSession(const std::string& path) : path_(path), document_(read_gltf(path)) {}

const Bounds3& FrameSession::framing(const RenderOptions& o) {
  const std::string key = o.scene + '\n' + o.variant + '\n' + o.animation + '\n' + o.camera + '\n' + o.look_at + '\n' +
                          o.camera_position + '\n' + o.camera_target;
  auto found = framings_.find(key);
  if (found == framings_.end()) found = framings_.emplace(key, animation_bounds(o, document_)).first;
  return found->second;
}

SessionFrame FrameSession::render(const std::vector<std::string>& arguments, RenderMonitor* monitor) {
  const RenderOptions o = parse_render_options(path_, arguments);
  SessionFrame out;
  out.warnings = ignored_option_warnings(o, false);
  const Bounds3& framing = this->framing(o);
  LoadedScene loaded = load_scene(o, document_, false);
  out.load_seconds = loaded.seconds;
  FramePlan plan = plan_frame(o, loaded.gltf, framing.empty() ? nullptr : &framing);
  const BuiltFrame built = build_frame(std::move(loaded), plan, &cache_);
  out.build_seconds = built.seconds;
  out.updated = built.updated;
  RenderResult result = render_frame(*built.scene, built.camera, plan.settings, monitor);
  if (plan.cost_layer) result.image.cost = tile_cost_image(result.profile);
  out.cancelled = result.stats.cancelled;
  const bool partial = samples_left(result.film, plan.settings.spp) > 0;
  out.write = frame_write_params(o, plan, built.camera, result.stats, partial);
  if (plan.denoise && !out.cancelled && result.image.samples_per_pixel > 0)
    denoise_planned_frame(plan, result.image, out.write.metadata);
  out.image = std::move(result.image);
  out.stats = result.stats;
  return out;
}

}  // namespace tessera
