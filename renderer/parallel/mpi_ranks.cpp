#include "renderer/parallel/mpi_ranks.h"

#include "renderer/parallel/call_watch.h"
#include "renderer/util/stop_clock.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <thread>

#include <mpi.h>

namespace tessera {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Adds the time from construction to destruction to a total: the communication time.
class Timed {
 public:
  explicit Timed(double& total) : total_(total), start_(Clock::now()) {}
  ~Timed() { total_ += seconds_since(start_); }
  Timed(const Timed&) = delete;
  Timed& operator=(const Timed&) = delete;

 private:
  double& total_;
  Clock::time_point start_;
};

// Rank 0's window holds the work counter, then two notes per rank that rank 0's watchdog
// reads: the number of the last collective call the rank entered, and how many signs of
// life (calls, batches taken) it has given.
constexpr MPI_Aint kCounter = 0;
MPI_Aint arrived_slot(int rank) { return 1 + 2 * static_cast<MPI_Aint>(rank); }
MPI_Aint beats_slot(int rank) { return arrived_slot(rank) + 1; }

// A waiting rank tests its request in a loop, as MPI_Wait does, then after this long sleeps
// between tests, giving its core to ranks that still render (an oversubscribed machine).
constexpr double kSpinSeconds = 0.01;
constexpr auto kNap = std::chrono::microseconds(200);
constexpr double kWatchEvery = 0.05;  // seconds between a waiting rank's looks at the notes

// Ranks other than 0 wait this much longer than --rank-timeout before they give up on rank 0
// (between calls or inside one): when rank 0 ends the job (MPI_Abort, or exiting), mpirun
// resumes and ends the others (SIGCONT, SIGTERM, SIGKILL a second later:
// odls_base_sigkill_timeout); a rank that had waited as long as rank 0 would then give a
// second verdict on a job already ending. So a job ends with one message.
constexpr double kOthersLater = 5.0;

// How long this rank waits for others (0: forever), from --rank-timeout.
double patience(double rank_timeout, int rank) {
  return rank_timeout > 0.0 ? rank_timeout + (rank == 0 ? 0.0 : kOthersLater) : 0.0;
}

// The call watch's verdict: one message, then the process ends with exit code 1 (the app's
// kExitFailure, as MPI_Abort(1) gives); mpirun then ends the other ranks. MPI itself cannot
// be called here (another thread, and the main one is inside MPI).
void stuck_in_mpi(int rank, double seconds) {
  const std::string who = rank == 0 ? "" : "rank " + std::to_string(rank) + ": ";
  std::fprintf(stderr,
               "tessera: %serror: an MPI call has not returned for %.3g s (a rank is stopped, hung or cut off, perhaps "
               "holding a lock in rank 0's window): ending the job\n",
               who.c_str(), seconds);
  std::fflush(stderr);
  std::_Exit(1);
}

std::string rank_list(const std::vector<int>& ranks) {
  std::string s = ranks.size() == 1 ? "rank " : "ranks ";
  for (std::size_t i = 0; i < ranks.size(); ++i) s += (i ? ", " : "") + std::to_string(ranks[i]);
  return s;
}

class MpiRankGroup : public RankGroup {
 public:
  MpiRankGroup(int rank, int size, double timeout)
      : rank_(rank),
        size_(size),
        timeout_(patience(timeout, rank)),
        notes_(2 * static_cast<std::size_t>(size)),
        watch_(timeout_, [rank](double seconds) { stuck_in_mpi(rank, seconds); }) {
    const MPI_Aint slots = rank == 0 ? arrived_slot(size) : 0;
    // Open MPI's one-sided components differ by network; say which to use rather than die.
    MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
    const int made = MPI_Win_allocate(slots * static_cast<MPI_Aint>(sizeof(long long)), sizeof(long long),
                                      MPI_INFO_NULL, MPI_COMM_WORLD, &slots_, &window_);
    MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_ARE_FATAL);
    if (made != MPI_SUCCESS)
      throw std::runtime_error(
          "MPI could not make the work counter's one-sided window on this network (over plain TCP, Open MPI's "
          "osc/ucx fails: run mpirun with --mca osc ^ucx)");
    std::fill_n(slots_, slots, 0LL);
    MPI_Win_lock_all(MPI_MODE_NOCHECK, window_);
    MPI_Barrier(MPI_COMM_WORLD);  // rank 0's slots are zero before anyone writes them
  }
  ~MpiRankGroup() override {
    watched([&] {
      MPI_Win_unlock_all(window_);
      MPI_Win_free(&window_);  // collective: waits for every rank
    });
  }

  int rank() const override { return rank_; }
  int size() const override { return size_; }

  void start_wave(std::size_t count) override {
    Timed timed(communication_);
    count_ = count;
    barrier_untimed();  // everyone is done with the last wave's counter
    if (rank_ == 0) {
      static const long long zero = 0;
      post_at_rank0(&zero, discarded_, 1, kCounter, MPI_REPLACE);
      complete();
    }
    barrier_untimed();
  }

  std::pair<std::size_t, std::size_t> next_items(std::size_t batch) override {
    Timed timed(communication_);
    batch_ = static_cast<long long>(batch);
    post_at_rank0(&batch_, &first_, 1, kCounter, MPI_SUM);
    note_beat();  // completed with the counter's operation
    complete();
    const std::size_t begin = std::min(static_cast<std::size_t>(first_), count_);
    return {begin, std::min(begin + batch, count_)};
  }

  std::vector<std::vector<char>> all_gather(const std::vector<char>& mine) override { return collect(mine, true); }
  std::vector<std::vector<char>> gather(const std::vector<char>& mine) override { return collect(mine, false); }

  bool any(bool flag) override {
    Timed timed(communication_);
    int mine = flag ? 1 : 0, result = 0;
    enter();
    MPI_Request request;
    watched([&] { MPI_Iallreduce(&mine, &result, 1, MPI_INT, MPI_LOR, MPI_COMM_WORLD, &request); });
    wait(request);
    return result != 0;
  }

  std::uint64_t sum(std::uint64_t value) override {
    Timed timed(communication_);
    unsigned long long mine = value, result = 0;
    enter();
    MPI_Request request;
    watched([&] { MPI_Iallreduce(&mine, &result, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, MPI_COMM_WORLD, &request); });
    wait(request);
    return result;
  }

  void barrier() override {
    Timed timed(communication_);
    barrier_untimed();
  }

  void alive() override {
    Timed timed(communication_);
    note_beat();
    complete();
  }

  void progress() override {
    int flag = 0;
    watched([&] { MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, MPI_STATUS_IGNORE); });
  }

  double communication_seconds() const override { return communication_; }

 private:
  // An MPI call that should return at once, watched by watch_ (a call that does not return
  // within the timeout ends the process).
  template <class Call>
  void watched(Call call) {
    const WatchedCall in(watch_);
    call();
  }

  void barrier_untimed() {
    enter();
    MPI_Request request;
    watched([&] { MPI_Ibarrier(MPI_COMM_WORLD, &request); });
    wait(request);
  }

  // Every rank's bytes in rank order, on every rank (`everyone`) or on rank 0: the sizes
  // first, then the bytes.
  std::vector<std::vector<char>> collect(const std::vector<char>& mine, bool everyone) {
    Timed timed(communication_);
    const int n = static_cast<int>(mine.size());
    std::vector<int> sizes(size_), offsets(size_);
    MPI_Request request;
    enter();
    watched([&] {
      if (everyone) MPI_Iallgather(&n, 1, MPI_INT, sizes.data(), 1, MPI_INT, MPI_COMM_WORLD, &request);
      else MPI_Igather(&n, 1, MPI_INT, sizes.data(), 1, MPI_INT, 0, MPI_COMM_WORLD, &request);
    });
    wait(request);
    const bool receives = everyone || rank_ == 0;
    const int total = place(sizes, offsets);
    std::vector<char> all(receives ? static_cast<std::size_t>(total) : 0);
    enter();
    watched([&] {
      if (everyone)
        MPI_Iallgatherv(mine.data(), n, MPI_CHAR, all.data(), sizes.data(), offsets.data(), MPI_CHAR, MPI_COMM_WORLD,
                        &request);
      else
        MPI_Igatherv(mine.data(), n, MPI_CHAR, all.data(), sizes.data(), offsets.data(), MPI_CHAR, 0, MPI_COMM_WORLD,
                     &request);
    });
    wait(request);
    if (!receives) return {};
    std::vector<std::vector<char>> out(size_);
    for (int r = 0; r < size_; ++r) out[r].assign(all.begin() + offsets[r], all.begin() + offsets[r] + sizes[r]);
    return out;
  }

  static int place(const std::vector<int>& sizes, std::vector<int>& offsets) {
    int total = 0;
    for (std::size_t r = 0; r < sizes.size(); ++r) offsets[r] = total, total += sizes[r];
    return total;
  }

  // Every one-sided operation is a read-modify-write at rank 0 (MPI_Rget_accumulate; the
  // notes advance with MPI_SUM, as the work counter does, which needs nothing of rank 0 while
  // it renders with shared memory or RDMA; other operations may wait for rank 0 to enter MPI,
  // serialising the ranks). Request-based, so that complete() can give up on a stopped rank 0
  // where rank 0 must serve them (TCP). The buffers must outlive the request (on the stack
  // they did not, which AddressSanitizer caught over TCP), even when complete() throws: the
  // operands are static or members.
  void post_at_rank0(const long long* operand, long long* result, int count, MPI_Aint slot, MPI_Op op) {
    const WatchedCall call(watch_);
    MPI_Rget_accumulate(operand, operand ? count : 0, MPI_LONG_LONG, result, count, MPI_LONG_LONG, 0, slot, count,
                        MPI_LONG_LONG, op, window_, &pending_[pending_count_++]);
  }
  static constexpr long long kOnes[2] = {1, 1};
  void note_beat() { post_at_rank0(kOnes, discarded_, 1, beats_slot(rank_), MPI_SUM); }
  // Before each collective call: every rank makes the same calls, so their counts agree. The
  // call and a sign of life, [arrived, beats], in one operation.
  void enter() {
    ++calls_;
    post_at_rank0(kOnes, discarded_, 2, arrived_slot(rank_), MPI_SUM);
    complete();
  }

  // Tests the posted operations in a loop, as wait() does a collective call: where rank 0
  // must serve them and is stopped, a blocking MPI_Win_flush would wait forever.
  void complete() {
    Clock::time_point start = Clock::now();
    StopClock stops;
    for (int done = 0;;) {
      watched([&] { MPI_Testall(pending_count_, pending_, &done, MPI_STATUSES_IGNORE); });
      if (done) break;
      start += stops.look().stopped;  // time this rank was stopped is not rank 0's silence
      if (timeout_ > 0.0 && seconds_since(start) > timeout_) throw RankTimeout(not_answered({0}));
      nap_after(start);
    }
    pending_count_ = 0;
  }

  // The notes of ranks [0, count): [arrived, beats] each, in notes_.
  void post_read_notes(int count) {
    post_at_rank0(nullptr, notes_.data(), 2 * count, arrived_slot(0), MPI_NO_OP);
  }

  // MPI_Wait with a watchdog. A waiting rank gives signs of life itself, and looks at the
  // notes: rank 0 gives up on the ranks that have not entered this call and have given no sign
  // of life for the timeout, naming them; another rank gives up when rank 0 has given none for
  // the timeout (while it waits for a healthy rank, rank 0 gives them).
  void wait(MPI_Request& request) {
    int done = 0;
    watched([&] { MPI_Test(&request, &done, MPI_STATUS_IGNORE); });
    if (done) return;
    const Clock::time_point start = Clock::now();
    const int observed = rank_ == 0 ? size_ : 1;  // rank 0 watches every rank; the others, rank 0
    std::vector<long long> beats(observed, -1);
    std::vector<Clock::time_point> seen(observed, start);
    Clock::time_point looked = start;
    StopClock stops;
    for (;;) {
      watched([&] { MPI_Test(&request, &done, MPI_STATUS_IGNORE); });
      if (done) return;
      if (const Clock::duration stopped = stops.look().stopped; stopped > Clock::duration::zero())
        for (Clock::time_point& t : seen) t += stopped;  // nor the others
      nap_after(start);
      if (timeout_ <= 0.0 || seconds_since(looked) < kWatchEvery) continue;
      looked = Clock::now();
      note_beat();
      post_read_notes(observed);
      complete();
      const std::vector<long long>& notes = notes_;
      std::vector<int> late;
      for (int r = 0; r < observed; ++r) {
        if (r == rank_) continue;
        if (notes[2 * r + 1] != beats[r]) beats[r] = notes[2 * r + 1], seen[r] = looked;
        if ((rank_ != 0 || notes[2 * r] < calls_) && seconds_since(seen[r]) > timeout_) late.push_back(r);
      }
      if (!late.empty()) throw RankTimeout(not_answered(late));
    }
  }

  static void nap_after(Clock::time_point start) {
    if (seconds_since(start) > kSpinSeconds) std::this_thread::sleep_for(kNap);
  }

  std::string not_answered(const std::vector<int>& late) const {
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%g s", timeout_);
    return rank_list(late) + (late.size() == 1 ? " has not answered for " : " have not answered for ") + seconds +
           " (stopped, hung or cut off): ending the job";
  }

  int rank_, size_;
  double timeout_;  // --rank-timeout, plus kOthersLater on ranks other than 0
  std::size_t count_ = 0;
  long long* slots_ = nullptr;
  long long calls_ = 0;
  double communication_ = 0.0;
  MPI_Win window_;
  // The one-sided operations' buffers and requests (post_at_rank0), at most two in flight.
  long long batch_ = 0, first_ = 0;  // the counter's operand and result
  long long discarded_[2] = {0, 0};  // the notes' results, never read
  std::vector<long long> notes_;
  MPI_Request pending_[2];
  int pending_count_ = 0;
  CallWatch watch_;  // last: its thread stops first
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

MpiSession::~MpiSession() {
  // Collective too; watched as the group's calls were (the group is gone by now), but given at
  // least kFinalizeSeconds: Open MPI's own teardown is not a rank's work between contacts, and a
  // short --rank-timeout must not fail a finished job here.
  constexpr double kFinalizeSeconds = 30.0;
  const double waits = patience(timeout_, rank_);
  CallWatch watch(waits > 0.0 ? std::max(waits, kFinalizeSeconds) : 0.0,
                  [rank = rank_](double seconds) { stuck_in_mpi(rank, seconds); });
  const WatchedCall call(watch);
  MPI_Finalize();
}

std::unique_ptr<RankGroup> MpiSession::ranks(double timeout) {
  timeout_ = timeout;
  return std::make_unique<MpiRankGroup>(rank_, size_, timeout);
}

void MpiSession::abort_all(int exit_code) {
  MPI_Abort(MPI_COMM_WORLD, exit_code);
  std::exit(exit_code);  // MPI_Abort does not return; this satisfies [[noreturn]]
}

}  // namespace tessera
