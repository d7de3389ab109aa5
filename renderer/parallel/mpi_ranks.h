// MPI for a distributed render (Open MPI from Debian): the session a process opens when a
// launcher (mpirun, srun) started it, and the RankGroup render_frame uses. The shared work
// counter is an integer in a one-sided window on rank 0, advanced with a remote fetch-and-add
// (MPI_Rget_accumulate), the paper's "next work item" variable; MPI is called from the main
// thread only (FUNNELED).
#pragma once

#include <memory>
#include <stdexcept>

#include "renderer/parallel/rank_group.h"

namespace tessera {

// True when built with MPI and started by an MPI launcher (its environment says so): only
// then is MPI initialised, so a plain run pays nothing for it.
bool launched_by_mpi();

// A rank stopped answering: the watchdog's verdict, naming it.
struct RankTimeout : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class MpiSession {
 public:
  MpiSession(int& argc, char**& argv);  // MPI_Init_thread; throws std::runtime_error
  ~MpiSession();  // MPI_Finalize
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }
  // The world's ranks as a RankGroup (the window is created collectively: every rank calls).
  // Its watchdog: rank 0, waiting in a collective call, throws RankTimeout naming the ranks
  // that have not reached the call and have given no sign of life (a call, a batch taken, a
  // wave of a frame rendered alone, waiting) for `timeout` seconds; another rank, waiting,
  // throws when rank 0 has given none for that long, or has not completed a one-sided
  // operation (the counter, the notes) for that long. 0: no watchdog.
  // Every MPI call of the group, and MPI_Finalize after it, is also watched by a thread that
  // ends the process when one has not returned within the timeout (renderer/parallel/call_watch.h).
  std::unique_ptr<RankGroup> ranks(double timeout);
  // Ends every rank's process (MPI_Abort), e.g. when this rank failed and the others wait.
  [[noreturn]] static void abort_all(int exit_code);

 private:
  int rank_ = 0, size_ = 1;
  double timeout_ = 0.0;  // the group's, for MPI_Finalize
};

}  // namespace tessera
