#include "renderer/mpi_ranks.h"

#include <cstdlib>
#include <stdexcept>
#include <string>

#include <mpi.h>

namespace tessera {
namespace {

class MpiRankGroup : public RankGroup {
 public:
  MpiRankGroup(int rank, int size) : rank_(rank), size_(size) {
    MPI_Win_allocate(rank == 0 ? sizeof(long long) : 0, sizeof(long long), MPI_INFO_NULL, MPI_COMM_WORLD, &counter_,
                     &window_);
    if (rank == 0) *counter_ = 0;
    MPI_Win_lock_all(MPI_MODE_NOCHECK, window_);
  }
  ~MpiRankGroup() override {
    MPI_Win_unlock_all(window_);
    MPI_Win_free(&window_);
  }

  int rank() const override { return rank_; }
  int size() const override { return size_; }

  void start_wave(std::size_t count) override {
    count_ = count;
    MPI_Barrier(MPI_COMM_WORLD);  // everyone is done with the last wave's counter
    if (rank_ == 0) {
      const long long zero = 0;
      MPI_Put(&zero, 1, MPI_LONG_LONG, 0, 0, 1, MPI_LONG_LONG, window_);
      MPI_Win_flush(0, window_);
    }
    MPI_Barrier(MPI_COMM_WORLD);
  }

  std::pair<std::size_t, std::size_t> next_items(std::size_t batch) override {
    const long long add = static_cast<long long>(batch);
    long long first = 0;
    MPI_Fetch_and_op(&add, &first, MPI_LONG_LONG, 0, 0, MPI_SUM, window_);
    MPI_Win_flush(0, window_);
    const std::size_t begin = std::min(static_cast<std::size_t>(first), count_);
    return {begin, std::min(begin + batch, count_)};
  }

  std::vector<std::vector<char>> all_gather(const std::vector<char>& mine) override {
    const int n = static_cast<int>(mine.size());
    std::vector<int> sizes(size_), offsets(size_);
    MPI_Allgather(&n, 1, MPI_INT, sizes.data(), 1, MPI_INT, MPI_COMM_WORLD);
    int total = 0;
    for (int r = 0; r < size_; ++r) offsets[r] = total, total += sizes[r];
    std::vector<char> all(static_cast<std::size_t>(total));
    MPI_Allgatherv(mine.data(), n, MPI_CHAR, all.data(), sizes.data(), offsets.data(), MPI_CHAR, MPI_COMM_WORLD);
    std::vector<std::vector<char>> out(size_);
    for (int r = 0; r < size_; ++r) out[r].assign(all.begin() + offsets[r], all.begin() + offsets[r] + sizes[r]);
    return out;
  }

  bool any(bool flag) override {
    int mine = flag ? 1 : 0, result = 0;
    MPI_Allreduce(&mine, &result, 1, MPI_INT, MPI_LOR, MPI_COMM_WORLD);
    return result != 0;
  }

  std::uint64_t sum(std::uint64_t value) override {
    unsigned long long mine = value, result = 0;
    MPI_Allreduce(&mine, &result, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
    return result;
  }

 private:
  int rank_, size_;
  std::size_t count_ = 0;
  long long* counter_ = nullptr;
  MPI_Win window_;
};

}  // namespace

bool launched_by_mpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
    if (std::getenv(name)) return true;
  return false;
}

MpiSession::MpiSession(int& argc, char**& argv) {
  int provided = 0;
  if (MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS)
    throw std::runtime_error("MPI could not be initialised");
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiSession::~MpiSession() { MPI_Finalize(); }

std::unique_ptr<RankGroup> MpiSession::ranks() const { return std::make_unique<MpiRankGroup>(rank_, size_); }

void MpiSession::abort_all(int exit_code) {
  MPI_Abort(MPI_COMM_WORLD, exit_code);
  std::exit(exit_code);  // MPI_Abort does not return; this satisfies [[noreturn]]
}

}  // namespace tessera
