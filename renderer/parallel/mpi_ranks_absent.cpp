// A build without MPI (no libopenmpi-dev): never launched by MPI, and no session to open.
#include "renderer/parallel/mpi_ranks.h"

#include <cstdlib>
#include <stdexcept>

namespace tessera {

bool launched_by_mpi() { return false; }

MpiSession::MpiSession(int&, char**&) {
  throw std::runtime_error("this tessera was built without MPI (install libopenmpi-dev and rebuild)");
}

MpiSession::~MpiSession() = default;

std::unique_ptr<RankGroup> MpiSession::ranks(double) { return nullptr; }

void MpiSession::abort_all(int exit_code) { std::exit(exit_code); }

}  // namespace tessera
