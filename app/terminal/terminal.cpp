#include "app/terminal/terminal.h"

#include <signal.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <vector>

namespace tessera {

namespace {

std::atomic<bool> g_resized{false};

void on_resize(int) { g_resized.store(true); }

// The pieces of a status line: each ends after a separator ("; ", ", ", " ").
std::vector<std::string> pieces(const std::string& line) {
  std::vector<std::string> out;
  std::string current;
  for (char c : line) {
    current += c;
    if (c == ' ') out.push_back(std::move(current)), current.clear();
  }
  if (!current.empty()) out.push_back(current);
  return out;
}

struct sigaction g_previous;

}  // namespace

int terminal_columns(int fd) {
  if (::isatty(fd) != 1) return 0;
  winsize size{};
  if (::ioctl(fd, TIOCGWINSZ, &size) != 0) return 0;
  return size.ws_col;
}

TerminalWidth::TerminalWidth() : columns_(terminal_columns(STDERR_FILENO)) {
  if (columns_ == 0) return;
  struct sigaction action {};
  action.sa_handler = on_resize;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  ::sigaction(SIGWINCH, &action, &g_previous);
}

TerminalWidth::~TerminalWidth() {
  if (columns_ != 0) ::sigaction(SIGWINCH, &g_previous, nullptr);
}

int TerminalWidth::columns() {
  if (columns_ != 0 && g_resized.exchange(false)) columns_ = terminal_columns(STDERR_FILENO);
  return columns_;
}

std::string elide_middle(const std::string& text, std::size_t width) {
  if (text.size() <= width) return text;
  if (width <= 3) return text.substr(0, width);
  const std::size_t keep = width - 3, tail = keep / 2 + keep % 2;
  return text.substr(0, keep - tail) + "..." + text.substr(text.size() - tail);
}

std::string fit_to_width(const std::string& line, int width) {
  if (width <= 0 || line.size() <= static_cast<std::size_t>(width)) return line;
  const std::size_t limit = static_cast<std::size_t>(width);
  const std::string indent = limit > 8 ? "  " : "";
  auto trimmed = [](std::string s) {
    while (!s.empty() && s.back() == ' ') s.pop_back();
    return s;
  };
  std::string out, current;
  for (std::string word : pieces(line)) {
    const bool space = word.back() == ' ';
    if (space) word.pop_back();
    const bool fresh = current.empty() || current == indent;
    if (!fresh && current.size() + word.size() > limit) {
      out += trimmed(current) + "\n";
      current = indent;
    }
    if (current.size() + word.size() > limit) word = elide_middle(word, limit - current.size());
    current += word;
    if (space) current += ' ';
  }
  return out + trimmed(current);
}

void print_status(const std::string& line) {
  const std::string text = fit_to_width(line, terminal_columns(STDERR_FILENO));
  std::fputs((text + "\n").c_str(), stderr);
}

}  // namespace tessera
