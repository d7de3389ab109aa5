// The commands of the tessera program: each adds its options to the command line and runs.
#pragma once

#include <CLI/CLI.hpp>

#include "app/cli/options.h"

namespace tessera {

class RankGroup;

void add_render_command(CLI::App& app, RenderOptions& options);
void add_info_command(CLI::App& app, InfoOptions& options);
void add_bench_command(CLI::App& app, BenchOptions& options);
void add_scaling_command(CLI::App& app, ScalingOptions& options);
void add_denoise_command(CLI::App& app, DenoiseOptions& options);

// `ranks`: the MPI ranks rendering together (null: this process alone).
int run_render(const RenderOptions& options, RankGroup* ranks = nullptr);
int run_info(const InfoOptions& options);
int run_bench(const BenchOptions& options);
int run_scaling(const ScalingOptions& options);
int run_denoise(const DenoiseOptions& options);

}  // namespace tessera
