#include "renderer/call_watch.h"

#include <algorithm>
#include <chrono>

namespace tessera {
namespace {

using Clock = std::chrono::steady_clock;

std::int64_t now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch()).count();
}

}  // namespace

CallWatch::CallWatch(double timeout, std::function<void(double)> stuck) : timeout_(timeout), stuck_(std::move(stuck)) {
  if (timeout_ > 0.0) thread_ = std::thread([this] { run(); });
}

CallWatch::~CallWatch() {
  if (!thread_.joinable()) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_one();
  thread_.join();
}

void CallWatch::enter() { entered_.store(now_ns(), std::memory_order_relaxed); }

// Looks every 50 ms (or a quarter of the timeout, if shorter): the verdict comes at most that
// late. The time inside a call is counted look by look, each look's share capped at
// kLongestLook: a longer gap between looks means this process itself was stopped (SIGSTOP,
// and mpirun's SIGCONT as it ends the job; a frozen machine), which is not the call's doing.
// Counted from the call's start, a rank stopped inside a call gave a second verdict when
// resumed.
void CallWatch::run() {
  constexpr double kLongestLook = 1.0;
  const auto every = std::chrono::duration<double>(std::min(0.05, timeout_ / 4));
  std::int64_t call = kOutside;  // the entered_ value of the call being counted
  double inside = 0.0;  // seconds of it counted
  std::int64_t looked = now_ns();
  std::unique_lock<std::mutex> lock(mutex_);
  while (!wake_.wait_for(lock, every, [this] { return stopping_; })) {
    const std::int64_t now = now_ns(), entered = entered_.load(std::memory_order_relaxed);
    const double since_look = std::min(static_cast<double>(now - looked) * 1e-9, kLongestLook);
    looked = now;
    if (entered == kOutside) {
      call = kOutside;
      continue;
    }
    if (entered != call) {
      call = entered;
      inside = std::min(static_cast<double>(now - entered) * 1e-9, since_look);
    } else {
      inside += since_look;
    }
    if (inside <= timeout_) continue;
    stuck_(inside);
    return;  // the verdict is given once
  }
}

}  // namespace tessera
