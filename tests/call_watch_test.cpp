// CallWatch (renderer/parallel/call_watch.h): a call that outlasts the timeout gets one verdict, no
// sooner than the timeout and at most a look (50 ms) plus scheduling later; time between
// calls, calls shorter than the timeout and time the process was stopped never do.
#include "renderer/parallel/call_watch.h"

#include <gtest/gtest.h>

#include <atomic>
#include <csignal>
#include <cstdlib>
#include <string>
#include <chrono>
#include <thread>

#include <unistd.h>

namespace tessera {
namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

TEST(CallWatch, ACallLongerThanTheTimeoutGetsOneVerdictAfterIt) {
  std::atomic<int> verdicts{0};
  std::atomic<double> lasted{0.0}, at{0.0};
  const double timeout = 0.2;
  CallWatch watch(timeout, [&](double seconds) {
    lasted = seconds;
    ++verdicts;
  });
  const Clock::time_point start = Clock::now();
  {
    const WatchedCall call(watch);
    while (verdicts == 0 && seconds_since(start) < 10.0) std::this_thread::sleep_for(milliseconds(1));
    at = seconds_since(start);
    std::this_thread::sleep_for(milliseconds(300));  // still inside: no second verdict
  }
  EXPECT_EQ(verdicts, 1);
  EXPECT_GT(lasted, timeout);
  EXPECT_GE(at, timeout);
  EXPECT_LT(at, timeout + 2.0) << "a look every 50 ms; 2 s allows for a loaded machine";
}

TEST(CallWatch, ShortCallsAndTheTimeBetweenThemGetNone) {
  std::atomic<int> verdicts{0};
  CallWatch watch(0.5, [&](double) { ++verdicts; });
  const Clock::time_point start = Clock::now();
  while (seconds_since(start) < 1.2) {  // far more than the timeout in all, in calls and out
    {
      const WatchedCall call(watch);
      std::this_thread::sleep_for(milliseconds(2));
    }
    std::this_thread::sleep_for(milliseconds(20));
  }
  std::this_thread::sleep_for(milliseconds(700));  // outside any call, past the timeout
  EXPECT_EQ(verdicts, 0);
}

// The process stopped (SIGSTOP) inside a call for twice the timeout, then resumed (SIGCONT
// from a child, as mpirun sends one when it ends a job): the stop is not the call's, at most
// one look's second of it counts, and a call that returns soon after gets no verdict.
// Counted from the call's start, it would (4 s > 2 s).
TEST(CallWatch, TimeTheProcessWasStoppedDoesNotCount) {
  std::atomic<int> verdicts{0};
  CallWatch watch(2.0, [&](double) { ++verdicts; });
  const Clock::time_point start = Clock::now();
  {
    const WatchedCall call(watch);
    const std::string resume = "(sleep 4; kill -CONT " + std::to_string(getpid()) + ") &";
    ASSERT_EQ(std::system(resume.c_str()), 0);
    raise(SIGSTOP);
    std::this_thread::sleep_for(milliseconds(100));
  }
  ASSERT_GE(seconds_since(start), 3.5) << "the process was not stopped: nothing tested";
  std::this_thread::sleep_for(milliseconds(200));  // a look after leaving
  EXPECT_EQ(verdicts, 0);
}

TEST(CallWatch, ATimeoutOfZeroWatchesNothing) {
  std::atomic<int> verdicts{0};
  CallWatch watch(0.0, [&](double) { ++verdicts; });
  {
    const WatchedCall call(watch);
    std::this_thread::sleep_for(milliseconds(100));
  }
  EXPECT_EQ(verdicts, 0);
}

}  // namespace
}  // namespace tessera
