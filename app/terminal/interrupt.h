// SIGINT and SIGTERM: the first asks the work in progress to stop (a render finishes the
// work in flight, keeps every finished sample and writes them, never over a finished frame:
// see app/commands/render_job.h); the second ends the process at once with exit code 130, removing
// the temporary file of any write in progress and leaving every earlier output untouched.
// install_interrupt_handlers() runs first thing in main, so a signal that arrives while a
// scene loads is not lost: the render that follows stops before it starts.
#pragma once

#include <atomic>

namespace tessera {

void install_interrupt_handlers();

// The ranks of an MPI job other than rank 0 stop as told but say nothing: rank 0 speaks for all.
void quiet_interrupt_messages();

// While alive, a first signal sets `cancel` (at once if one has already arrived).
class InterruptHandler {
 public:
  explicit InterruptHandler(std::atomic<bool>& cancel);
  ~InterruptHandler();
  InterruptHandler(const InterruptHandler&) = delete;
  InterruptHandler& operator=(const InterruptHandler&) = delete;

  bool interrupted() const;
};

}  // namespace tessera
