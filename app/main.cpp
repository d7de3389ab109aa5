// tessera: a path tracer for glTF 2.0 scenes. Exit codes: see app/cli/exit_codes.h.
#include <cstdio>
#include <exception>
#include <memory>
#include <string>
#include <new>

#include <fmt/format.h>

#include "app/cli/command_line.h"
#include "app/cli/command_parser.h"
#include "app/commands/commands.h"
#include "app/cli/exit_codes.h"
#include "app/terminal/interrupt.h"
#include "app/isa_dispatch.h"
#include "imageio/image_input.h"
#include "imageio/image_output.h"
#include "renderer/parallel/mpi_ranks.h"
#include "imageio/resume_layers.h"
#include "scene_io/base/load_error.h"

int main(int argc, char** argv) {
  using namespace tessera;
  if (const int code = run_chosen_isa(argv); code >= 0) return code;
  install_interrupt_handlers();
  CLI::App app{"tessera " + tessera_version() +
               ": a physically based path tracer for glTF 2.0 scenes.\n\n"
               "Exit codes: 0 success, 1 internal or system failure (out of memory, disk full),\n"
               "2 bad usage or bad input (with one message naming the file or option),\n"
               "130 interrupted.\n\n"
               "Environment: TESSERA_ISA=auto|x86-64|x86-64-v3 chooses the build for an instruction set\n"
               "(auto: AVX2/FMA when the CPU has them; the image is the same bit for bit).",
               "tessera"};
  app.require_subcommand(1);
  app.set_version_flag("--version", version_line());
  RenderOptions render;
  InfoOptions info;
  BenchOptions bench;
  ScalingOptions scaling;
  DenoiseOptions denoise;
  add_render_command(app, render);
  render.command_line = shell_command_line(argc, argv);  // for the EXR header
  add_info_command(app, info);
  add_bench_command(app, bench);
  add_scaling_command(app, scaling);
  add_denoise_command(app, denoise);
  if (const int code = parse_command_line(app, argc, argv); code >= 0) return code;
  // Under an MPI launcher every rank runs this; a rank that fails ends them all, so that none
  // waits forever for it, and says which rank it was.
  std::unique_ptr<MpiSession> mpi;
  std::unique_ptr<RankGroup> ranks;
  std::string who;
  auto fail = [&](int code, const std::string& message) {
    fmt::print(stderr, "tessera: {}error: {}\n", who, message);
    if (mpi && mpi->size() > 1) MpiSession::abort_all(code);
    return code;
  };
  try {
    if (launched_by_mpi()) {
      mpi = std::make_unique<MpiSession>(argc, argv);
      if (mpi->rank() > 0) {
        who = fmt::format("rank {}: ", mpi->rank());
        quiet_interrupt_messages();
      }
    }
    if (app.got_subcommand("render")) {
      if (mpi) ranks = mpi->ranks(render.rank_timeout);
      const int code = run_render(render, ranks.get());
      if (ranks) ranks->barrier();  // watched: freeing the window below waits for every rank unwatched
      ranks.reset();  // its window is freed collectively, before MPI_Finalize
      return code;
    }
    if (app.got_subcommand("info")) return run_info(info);
    if (app.got_subcommand("scaling")) return run_scaling(scaling);
    if (app.got_subcommand("denoise")) return run_denoise(denoise);
    return run_bench(bench);
  } catch (const SceneLoadError& e) {
    return fail(kExitBadInput, e.what());
  } catch (const OutputPathError& e) {  // checked before rendering
    return fail(kExitBadInput, e.what());
  } catch (const ResumeError& e) {  // --resume: not resumable, damaged
    return fail(kExitBadInput, e.what());
  } catch (const ImageInputError& e) {  // denoise: an unreadable EXR
    return fail(kExitBadInput, e.what());
  } catch (const UsageError& e) {
    return fail(kExitBadInput, e.what());
  } catch (const std::invalid_argument& e) {  // unreadable environment map and the like
    return fail(kExitBadInput, e.what());
  } catch (const std::bad_alloc&) {
    return fail(kExitFailure, "out of memory");
  } catch (const std::exception& e) {
    return fail(kExitFailure, e.what());
  }
}
