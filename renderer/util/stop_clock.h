// Time this process itself was stopped (SIGSTOP; mpirun's SIGCONT as it ends a job; a frozen
// machine) is no one else's doing: a watchdog that looks at its clock often (every 50 ms or
// far less) reads an interval longer than kLongestGap between two looks as such a stop, and
// counts only kLongestGap of it. Without this a rank stopped while waiting, or inside an MPI
// call, gave a second verdict on the others when mpirun resumed it to end the job.
#pragma once

#include <algorithm>
#include <chrono>

namespace tessera {

class StopClock {
 public:
  using Clock = std::chrono::steady_clock;
  static constexpr Clock::duration kLongestGap = std::chrono::seconds(1);

  struct Gap {
    Clock::duration counted;  // the time since the last look that counts, at most kLongestGap
    Clock::duration stopped;  // the rest: this process was stopped
  };

  // The time since the last look (or construction), split.
  Gap look() {
    const Clock::time_point now = Clock::now();
    const Clock::duration gap = now - last_;
    last_ = now;
    const Clock::duration counted = std::min(gap, Clock::duration(kLongestGap));
    return {counted, gap - counted};
  }

 private:
  Clock::time_point last_ = Clock::now();
};

}  // namespace tessera
