// What fits on the terminal: its width (read with TIOCGWINSZ, again after each SIGWINCH),
// and text shortened to fit it, so that no status line wraps.
#pragma once

#include <string>

namespace tessera {

// Columns of the terminal on `fd`; 0 when it is not a terminal (or says no width).
int terminal_columns(int fd);

// Keeps the width of stderr's terminal, re-read after the window is resized (SIGWINCH,
// handled while one of these lives).
class TerminalWidth {
 public:
  TerminalWidth();
  ~TerminalWidth();
  TerminalWidth(const TerminalWidth&) = delete;
  TerminalWidth& operator=(const TerminalWidth&) = delete;
  int columns();  // 0: stderr is not a terminal

 private:
  int columns_ = 0;
};

// `text` with its middle replaced by "..." to be at most `width` characters (a path keeps
// its start and its file name).
std::string elide_middle(const std::string& text, std::size_t width);

// `line` broken into lines of at most `width` characters, after "; " or ", " or a space,
// the following lines indented by two; a piece too long alone (a path) is elided in its
// middle. Width 0: the line as it is.
std::string fit_to_width(const std::string& line, int width);

// Prints a status line on stderr, fitted to the terminal's width when stderr is one.
void print_status(const std::string& line);

}  // namespace tessera
