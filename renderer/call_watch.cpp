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
// late.
void CallWatch::run() {
  const auto every = std::chrono::duration<double>(std::min(0.05, timeout_ / 4));
  std::unique_lock<std::mutex> lock(mutex_);
  while (!wake_.wait_for(lock, every, [this] { return stopping_; })) {
    const std::int64_t entered = entered_.load(std::memory_order_relaxed);
    if (entered == kOutside) continue;
    const double seconds = static_cast<double>(now_ns() - entered) * 1e-9;
    if (seconds <= timeout_) continue;
    stuck_(seconds);
    return;  // the verdict is given once
  }
}

}  // namespace tessera
