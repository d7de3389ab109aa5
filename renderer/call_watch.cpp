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

CallWatch::CallWatch(double timeout, std::function<void(double)> stuck)
    : timeout_(timeout), stuck_(std::move(stuck)), looked_(now_ns()) {
  // A look every 50 ms (or a quarter of the timeout, if shorter): the verdict comes at most
  // that late.
  if (timeout_ > 0.0)
    thread_.emplace(std::chrono::duration<double>(std::min(0.05, timeout_ / 4)), [this] { return look(); });
}

void CallWatch::enter() { entered_.store(now_ns(), std::memory_order_relaxed); }

// The time inside a call is counted look by look, each look's share capped at kLongestLook: a
// longer gap between looks means this process itself was stopped (SIGSTOP, and mpirun's
// SIGCONT as it ends the job; a frozen machine), which is not the call's doing. Counted from
// the call's start, a rank stopped inside a call gave a second verdict when resumed.
bool CallWatch::look() {
  constexpr double kLongestLook = 1.0;
  const std::int64_t now = now_ns(), entered = entered_.load(std::memory_order_relaxed);
  const double since_look = std::min(static_cast<double>(now - looked_) * 1e-9, kLongestLook);
  looked_ = now;
  if (entered == kOutside) {
    call_ = kOutside;
    return true;
  }
  if (entered != call_) {
    call_ = entered;
    inside_ = std::min(static_cast<double>(now - entered) * 1e-9, since_look);
  } else {
    inside_ += since_look;
  }
  if (inside_ <= timeout_) return true;
  stuck_(inside_);
  return false;  // the verdict is given once
}

}  // namespace tessera
