// tessera denoise: a rendered EXR with half buffers in, the denoised frame out (see
// denoiser/denoise.h and docs/usage.md).
#include <chrono>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "app/commands/commands.h"
#include "app/cli/exit_codes.h"
#include "app/frame/frame_denoise.h"
#include "app/terminal/terminal.h"
#include "imageio/image_input.h"
#include "imageio/image_output.h"

namespace tessera {

void add_denoise_command(CLI::App& app, DenoiseOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "denoise",
      "Denoise an EXR that tessera rendered: feature-guided regression (NFOR) on its half buffers\n"
      "(even.R/G/B, odd.R/G/B), guided by Albedo.R/G/B and N.X/Y/Z (and Z, even.Albedo.*, odd.Albedo.*,\n"
      "even.N.*, odd.N.*, variance.R/G/B, spp when present).");
  cmd->add_option("input", o.input, "The rendered EXR")->required();
  cmd->add_option("-o,--output", o.output,
                  "Output EXR: R,G,B,A denoised, noisy.R/G/B the input's beauty, every other channel (not the resume layers) and "
                  "the header carried over")
      ->required();
  cmd->add_option("--preview", o.preview, "Also write the denoised frame as a display-referred image (sRGB), e.g. out.png");
  add_display_options(cmd, o.display, "Preview");
  cmd->add_option("--threads", o.threads, "Threads [default: all cores]")->check(CLI::Range(1, 1024));
  cmd->add_flag("-q,--quiet", o.quiet, "No summary (errors still print)");
}

int run_denoise(const DenoiseOptions& o) {
  if (!is_exr_path(o.output)) throw UsageError(o.output + ": the denoised frame must be written as .exr");
  check_output_path(o.output);  // before any work
  if (!o.preview.empty()) check_output_path(o.preview);
  ImageWriteParams preview;  // the view checked before any work, as render does
  preview.display = plan_display(o.display);
  preview.exposure = o.display.exposure;
  const DisplayOptions plain;
  const std::pair<const char*, bool> looks[] = {{"--exposure", o.display.exposure != plain.exposure},
                                                {"--view-transform", o.display.view_transform != plain.view_transform},
                                                {"--ocio-config", !o.display.ocio_config.empty()}};
  for (const auto& [name, set] : looks)
    if (set && o.preview.empty()) fmt::print(stderr, "tessera: warning: {}: applies to --preview, which is not given\n", name);
  ExrChannels exr = read_exr_channels(o.input);
  std::vector<std::string> missing;
  for (const std::string& name : denoise_channels())
    if (!exr.has(name)) missing.push_back(name);
  if (!missing.empty())
    throw UsageError(fmt::format("{}: cannot be denoised: missing channel{} {} (render it with --denoise, or with "
                                 "--aov halves,albedo,normal)",
                                 o.input, missing.size() > 1 ? "s" : "", fmt::join(missing, ", ")));
  const FrameWindow window = exr.window;
  const DenoiseParams params = denoise_params(o.threads, exr.sampler);
  FrameImage frame = frame_from_exr(std::move(exr));
  const double seconds = denoise_frame(frame, params);
  ImageWriteParams write;
  write.header_from = o.input;
  write.window = window;
  write_image(o.output, frame, write);
  if (!o.preview.empty()) write_image(o.preview, frame, preview);
  if (!o.quiet)
    print_status(fmt::format("tessera: denoised {} ({}x{}) in {:.2f} s; wrote {}{}", o.input, frame.width, frame.height,
                             seconds, o.output, o.preview.empty() ? "" : " and " + o.preview));
  return kExitSuccess;
}

}  // namespace tessera
