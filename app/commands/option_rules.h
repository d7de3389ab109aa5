// Rules between render options: the --quick preset, options that conflict (refused), and
// options that have no effect with the others given (a warning each, naming why). Applied
// before anything is loaded; docs/usage.md lists them ("Options without effect").
#pragma once

#include <string>
#include <vector>

#include "app/cli/options.h"

namespace tessera {

// Whether the command line gave `name` ("--spp").
bool given(const RenderOptions& o, const char* name);

// --quick: --resolution-scale 0.25, --spp 4, --max-bounces 4, each unless given.
void apply_quick_preset(RenderOptions& o);

// Throws UsageError (exit 2) for options that contradict each other.
void check_option_conflicts(const RenderOptions& o);

// One line per given option that changes nothing here: "--focus-distance: has no effect
// without --aperture (...)". `distributed`: more than one MPI rank renders.
std::vector<std::string> ignored_option_warnings(const RenderOptions& o, bool distributed);

}  // namespace tessera
