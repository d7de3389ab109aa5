// Render progress on stderr: a one-line bar with percent, elapsed, ETA and samples/s when
// stderr is a terminal, a plain line every few seconds otherwise, nothing when quiet. The
// total follows the monitor's, which adaptive sampling lowers as pixels converge.
#pragma once

#include <atomic>
#include <chrono>
#include <optional>
#include <string>

#include "app/terminal/terminal.h"
#include "renderer/util/periodic_thread.h"
#include "renderer/render/render.h"

namespace tessera {

struct ProgressOptions {
  std::uint64_t total_samples = 0;
  bool quiet = false;
  std::string label;  // starts every line, e.g. which run of a series this is
  bool erase_when_done = false;  // a terminal's bar vanishes at the end (the caller prints a result)
  bool adaptive = false;  // also say how many pixels converged
};

class ProgressDisplay {
 public:
  ProgressDisplay(const RenderMonitor& monitor, ProgressOptions options);
  ~ProgressDisplay();  // stops the display and ends the line
  ProgressDisplay(const ProgressDisplay&) = delete;
  ProgressDisplay& operator=(const ProgressDisplay&) = delete;

 private:
  void draw(bool final_line);
  std::string converged_text() const;

  const RenderMonitor& monitor_;
  ProgressOptions options_;
  bool terminal_;
  TerminalWidth width_;
  std::chrono::steady_clock::time_point start_;
  std::optional<PeriodicThread> redraw_;  // last: it draws with the members above
};

std::string format_duration(double seconds);

// What one progress line shows.
struct ProgressFields {
  std::string label;
  double fraction = 0.0, elapsed = 0.0, eta = -1.0, samples_per_second = 0.0;
  std::string converged;  // ", 62% of pixels converged", or empty
};

// The bar for a terminal `columns` wide (0: unknown, the whole line), shorter than it so it
// never wraps: the converged share, then the words, the rate and the elapsed time drop and
// the bar narrows (to 10) before it goes; at 40 columns it still shows bar, percent and ETA.
std::string terminal_progress_line(const ProgressFields& f, int columns);

}  // namespace tessera
