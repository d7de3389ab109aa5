// A thread that calls `tick` every `period` until the object is destroyed or `tick` returns
// false: the progress display's redraws, the call watch's looks. Destruction wakes it at once.
#pragma once

#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>

namespace tessera {

class PeriodicThread {
 public:
  PeriodicThread() = default;  // no thread
  PeriodicThread(std::chrono::duration<double> period, std::function<bool()> tick)
      : period_(period), tick_(std::move(tick)), thread_([this] { run(); }) {}
  ~PeriodicThread() { stop(); }
  PeriodicThread(const PeriodicThread&) = delete;
  PeriodicThread& operator=(const PeriodicThread&) = delete;

  // Stops and joins the thread (after its current tick); idempotent.
  void stop() {
    if (!thread_.joinable()) return;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stopping_ = true;
    }
    wake_.notify_all();
    thread_.join();
  }

 private:
  void run() {
    std::unique_lock<std::mutex> lock(mutex_);
    while (!wake_.wait_for(lock, period_, [this] { return stopping_; }))
      if (!tick_()) return;
  }

  std::chrono::duration<double> period_{0.0};
  std::function<bool()> tick_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;
  std::thread thread_;  // last: started once the members it uses are
};

}  // namespace tessera
