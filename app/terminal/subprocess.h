// Runs another program and waits for it: tessera scaling launches `mpirun ... tessera render`
// for its multi-rank runs.
#pragma once

#include <string>
#include <vector>

namespace tessera {

// This program's own path (/proc/self/exe), to launch it again.
std::string own_executable();

// Runs argv[0] (searched in PATH) with its standard output and error written to `log_path`;
// returns its exit code, 128 + the signal that ended it, or 127 when it could not start.
int run_program(const std::vector<std::string>& argv, const std::string& log_path);

}  // namespace tessera
