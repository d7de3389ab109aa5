#include "renderer/parallel/call_watch.h"

#include <algorithm>
#include <chrono>

namespace tessera {
namespace {

std::int64_t now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(StopClock::Clock::now().time_since_epoch()).count();
}

}  // namespace

CallWatch::CallWatch(double timeout, std::function<void(double)> stuck) : timeout_(timeout), stuck_(std::move(stuck)) {
  // A look every 50 ms (or a quarter of the timeout, if shorter): the verdict comes at most
  // that late.
  if (timeout_ > 0.0)
    thread_.emplace(std::chrono::duration<double>(std::min(0.05, timeout_ / 4)), [this] { return look(); });
}

void CallWatch::enter() { entered_.store(now_ns(), std::memory_order_relaxed); }

// The time inside a call is counted look by look, without the time this process was stopped
// (renderer/util/stop_clock.h).
bool CallWatch::look() {
  const double counted = std::chrono::duration<double>(stops_.look().counted).count();
  const std::int64_t entered = entered_.load(std::memory_order_relaxed);
  if (entered == kOutside) {
    call_ = kOutside;
    return true;
  }
  if (entered != call_) {  // a new call: since it began, at most this look's share
    call_ = entered;
    inside_ = std::min(static_cast<double>(now_ns() - entered) * 1e-9, counted);
  } else {
    inside_ += counted;
  }
  if (inside_ <= timeout_) return true;
  stuck_(inside_);
  return false;  // the verdict is given once
}

}  // namespace tessera
