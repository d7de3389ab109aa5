// A thread that ends the process when the thread it watches has spent longer than a timeout
// inside one call: for calls nothing can interrupt from within. An MPI one-sided operation
// can spin inside Open MPI on a lock in rank 0's window that a stopped rank holds (osc/rdma
// and osc/sm take one for accumulates they cannot do as one hardware atomic); the watchdog
// between calls (renderer/parallel/mpi_ranks.cpp) never gets control back there.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>

#include "renderer/util/periodic_thread.h"
#include "renderer/util/stop_clock.h"

namespace tessera {

class CallWatch {
 public:
  // `stuck` runs once, on the watch thread, with the seconds the call has lasted, when one
  // call has lasted longer than `timeout` seconds; it is meant to end the process. A
  // timeout of 0 watches nothing (no thread).
  CallWatch(double timeout, std::function<void(double seconds)> stuck);
  CallWatch(const CallWatch&) = delete;
  CallWatch& operator=(const CallWatch&) = delete;

  // The watched thread enters and leaves a call (two atomic stores: cheap beside any call
  // worth watching). Calls do not nest.
  void enter();
  void leave() { entered_.store(kOutside, std::memory_order_relaxed); }

 private:
  static constexpr std::int64_t kOutside = INT64_MIN;
  bool look();  // false once the verdict is given

  double timeout_;
  std::function<void(double)> stuck_;
  std::atomic<std::int64_t> entered_{kOutside};  // steady-clock nanoseconds at enter()
  std::int64_t call_ = kOutside;  // the look's: the entered_ value of the call being counted
  double inside_ = 0.0;  // seconds of it counted
  StopClock stops_;  // the time between looks
  std::optional<PeriodicThread> thread_;  // last: it looks at the members above
};

// enter() for the lifetime of the object.
class WatchedCall {
 public:
  explicit WatchedCall(CallWatch& watch) : watch_(watch) { watch_.enter(); }
  ~WatchedCall() { watch_.leave(); }
  WatchedCall(const WatchedCall&) = delete;
  WatchedCall& operator=(const WatchedCall&) = delete;

 private:
  CallWatch& watch_;
};

}  // namespace tessera
