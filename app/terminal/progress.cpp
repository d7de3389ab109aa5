#include "app/terminal/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include <fmt/format.h>

namespace tessera {

std::string format_duration(double seconds) {
  if (!(seconds >= 0.0) || seconds > 1e7) return "--:--";
  const long s = static_cast<long>(seconds + 0.5);
  if (s >= 3600) return fmt::format("{}:{:02}:{:02}", s / 3600, (s / 60) % 60, s % 60);
  return fmt::format("{:02}:{:02}", s / 60, s % 60);
}

std::string terminal_progress_line(const ProgressFields& f, int columns) {
  const std::string pct = fmt::format("{:5.1f}%", 100.0 * f.fraction);
  const std::string elapsed = format_duration(f.elapsed), eta = format_duration(f.eta);
  const double rate = f.samples_per_second * 1e-6;
  const std::string texts[] = {
      fmt::format("{}  {} elapsed  ETA {}  {:.2f} M samples/s{}", pct, elapsed, eta, rate, f.converged),
      fmt::format("{}  {} elapsed  ETA {}  {:.2f} M samples/s", pct, elapsed, eta, rate),
      fmt::format("{}  {}  ETA {}  {:.2f} Ms/s", pct, elapsed, eta, rate),
      fmt::format("{}  ETA {}", pct, eta),
      pct,
  };
  auto bar = [&](int inner) {
    const int filled = std::clamp(static_cast<int>(f.fraction * inner), 0, inner);
    return "[" + std::string(filled, '#') + std::string(inner - filled, '.') + "] ";
  };
  constexpr int kWidest = 30, kNarrowest = 10;
  if (columns <= 0) return f.label + bar(kWidest) + texts[0];
  const int room = columns - 1;  // the last column left free: some terminals wrap on it
  for (const std::string& text : texts) {
    const int inner = std::min(kWidest, room - static_cast<int>(f.label.size() + text.size()) - 3);
    if (inner >= kNarrowest) return f.label + bar(inner) + text;
  }
  for (const std::string& text : texts)
    if (static_cast<int>(f.label.size() + text.size()) <= room) return f.label + text;
  return elide_middle(f.label + pct, static_cast<std::size_t>(std::max(room, 0)));
}

ProgressDisplay::ProgressDisplay(const RenderMonitor& monitor, ProgressOptions options)
    : monitor_(monitor), options_(std::move(options)), terminal_(::isatty(STDERR_FILENO) == 1),
      start_(std::chrono::steady_clock::now()) {
  // A terminal gets a live bar; a log gets a line every 10 s.
  if (!options_.quiet && options_.total_samples > 0)
    redraw_.emplace(std::chrono::duration<double>(terminal_ ? 0.2 : 10.0), [this] {
      draw(false);
      return true;
    });
}

ProgressDisplay::~ProgressDisplay() {
  if (!redraw_) return;
  redraw_.reset();  // stops it
  draw(true);
}

std::string ProgressDisplay::converged_text() const {
  const std::uint64_t pixels = monitor_.pixels_total.load(std::memory_order_relaxed);
  if (!options_.adaptive || pixels == 0) return "";
  const double share = static_cast<double>(monitor_.pixels_converged.load(std::memory_order_relaxed)) /
                       static_cast<double>(pixels);
  return fmt::format(", {:.0f}% of pixels converged", 100.0 * share);
}

void ProgressDisplay::draw(bool final_line) {
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const std::uint64_t done = monitor_.samples_done.load(std::memory_order_relaxed);
  const std::uint64_t live = monitor_.samples_total.load(std::memory_order_relaxed);
  const std::uint64_t total = std::max(live ? live : options_.total_samples, done);
  const double fraction = total ? static_cast<double>(done) / total : 1.0;
  const double rate = elapsed > 0 ? done / elapsed : 0.0;
  const double eta = rate > 0 ? (total - done) / rate : -1.0;
  std::string line;
  if (terminal_ && final_line && options_.erase_when_done) {
    line = "\r\x1b[K";  // clear the bar
  } else if (terminal_) {
    line = "\r\x1b[K" + terminal_progress_line({options_.label, fraction, elapsed, eta, rate, converged_text()},
                                               width_.columns());
    if (final_line) line += "\n";
  } else {
    if (final_line) return;  // the summary follows; a log needs no closing bar
    line = fmt::format("{}rendering: {:.1f}% done, {} elapsed, ETA {}, {:.2f} M samples/s{}\n", options_.label,
                       100.0 * fraction, format_duration(elapsed), format_duration(eta), rate * 1e-6,
                       converged_text());
  }
  std::fputs(line.c_str(), stderr);
  std::fflush(stderr);
}

}  // namespace tessera
