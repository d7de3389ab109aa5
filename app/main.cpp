// tessera: a path tracer for glTF 2.0 scenes. Exit codes: see app/exit_codes.h.
#include <cstdio>
#include <exception>
#include <new>

#include <fmt/format.h>

#include "app/commands.h"
#include "app/exit_codes.h"
#include "app/interrupt.h"
#include "renderer/image_input.h"
#include "renderer/image_output.h"
#include "renderer/resume_layers.h"
#include "scene_io/load_error.h"

int main(int argc, char** argv) {
  using namespace tessera;
  install_interrupt_handlers();
  CLI::App app{"tessera " + tessera_version() +
               ": a physically based path tracer for glTF 2.0 scenes.\n\n"
               "Exit codes: 0 success, 1 internal or system failure (out of memory, disk full),\n"
               "2 bad usage or bad input (with one message naming the file or option),\n"
               "130 interrupted.",
               "tessera"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "tessera " + tessera_version());
  RenderOptions render;
  InfoOptions info;
  BenchOptions bench;
  ScalingOptions scaling;
  DenoiseOptions denoise;
  add_render_command(app, render);
  add_info_command(app, info);
  add_bench_command(app, bench);
  add_scaling_command(app, scaling);
  add_denoise_command(app, denoise);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    fmt::print(stderr, "tessera: error: {}\nRun 'tessera --help' or 'tessera COMMAND --help' for usage.\n", e.what());
    return kExitBadInput;
  }
  try {
    if (app.got_subcommand("render")) return run_render(render);
    if (app.got_subcommand("info")) return run_info(info);
    if (app.got_subcommand("scaling")) return run_scaling(scaling);
    if (app.got_subcommand("denoise")) return run_denoise(denoise);
    return run_bench(bench);
  } catch (const SceneLoadError& e) {
    fmt::print(stderr, "tessera: error: {}\n", e.what());
    return kExitBadInput;
  } catch (const OutputPathError& e) {  // checked before rendering
    fmt::print(stderr, "tessera: error: {}\n", e.what());
    return kExitBadInput;
  } catch (const ResumeError& e) {  // --resume: not resumable, damaged
    fmt::print(stderr, "tessera: error: {}\n", e.what());
    return kExitBadInput;
  } catch (const ImageInputError& e) {  // denoise: an unreadable EXR
    fmt::print(stderr, "tessera: error: {}\n", e.what());
    return kExitBadInput;
  } catch (const UsageError& e) {
    fmt::print(stderr, "tessera: error: {}\n", e.what());
    return kExitBadInput;
  } catch (const std::invalid_argument& e) {  // unreadable environment map and the like
    fmt::print(stderr, "tessera: error: {}\n", e.what());
    return kExitBadInput;
  } catch (const std::bad_alloc&) {
    fmt::print(stderr, "tessera: error: out of memory\n");
    return kExitFailure;
  } catch (const std::exception& e) {
    fmt::print(stderr, "tessera: error: {}\n", e.what());
    return kExitFailure;
  }
}
