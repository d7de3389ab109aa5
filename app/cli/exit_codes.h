// The exit codes tessera documents (docs/usage.md, tessera --help).
#pragma once

#include <stdexcept>

namespace tessera {

enum ExitCode : int {
  kExitSuccess = 0,
  kExitFailure = 1,  // internal failure, or the system failed us (out of memory, disk full, a hung MPI rank)
  kExitBadInput = 2,  // bad usage, bad option value, unreadable or malformed input
  kExitInterrupted = 130,  // stopped by SIGINT/SIGTERM
};

// Thrown for bad usage or input that is not a scene file problem; main maps it to 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace tessera
