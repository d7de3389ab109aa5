// Progress and summary on a terminal never wrap (docs/usage.md, "Progress and summary"):
// the bar drops fields and narrows to the terminal's width (TIOCGWINSZ, again after
// SIGWINCH), and long summary lines break and elide paths. Run for real under a
// pseudo-terminal of 40, 80 and 200 columns.
#include <gtest/gtest.h>

#include <poll.h>
#include <pty.h>
#include <signal.h>
#include <sys/ioctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "app/terminal/progress.h"
#include "app/terminal/terminal.h"
#include "tests/test_support.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;

// ---- the line for a width -----------------------------------------------------------------

TEST(ProgressLine, FitsEveryWidthAndKeepsWhatMattersMost) {
  const ProgressFields full{"frame 12 (3 of 48): ", 0.438, 35.2, 45.0, 1.76e6, ", 62% of pixels converged"};
  for (int columns = 1; columns <= 250; ++columns) {
    const std::string line = terminal_progress_line(full, columns);
    EXPECT_LE(line.size(), static_cast<std::size_t>(columns - 1 > 0 ? columns - 1 : 0)) << columns << ": " << line;
  }
  const ProgressFields plain{"", 0.438, 35.2, 45.0, 1.76e6, ""};
  // 40 columns: a bar, the percentage and the ETA.
  const std::string narrow = terminal_progress_line(plain, 40);
  EXPECT_EQ(narrow, "[########...........]  43.8%  ETA 00:45") << narrow;  // 39 characters
  // Wide: everything, with the 30-character bar.
  EXPECT_EQ(terminal_progress_line(plain, 200),
            "[#############.................]  43.8%  00:35 elapsed  ETA 00:45  1.76 M samples/s");
  EXPECT_EQ(terminal_progress_line(plain, 0), terminal_progress_line(plain, 200));  // width unknown
}

TEST(FitToWidth, BreaksAtSeparatorsAndElidesWhatIsTooLong) {
  const std::string line = "tessera: /very/long/path/to/a/scene/directory/somewhere/deep/scene.glb: 12 triangles; "
                           "load 0.00 s, BVH and textures 0.02 s (BVH 0.02 s), render 0.50 s; background white";
  const std::string fitted = fit_to_width(line, 40);
  std::string joined;
  std::size_t start = 0;
  for (std::size_t end; start <= fitted.size(); start = end + 1) {
    end = fitted.find('\n', start);
    if (end == std::string::npos) end = fitted.size();
    const std::string part = fitted.substr(start, end - start);
    EXPECT_LE(part.size(), 40u) << part;
    joined += (joined.empty() ? "" : " ") + part.substr(part.find_first_not_of(' '));
  }
  EXPECT_NE(fitted.find("\n  /very/long/path/t...re/deep/scene.glb:\n"), std::string::npos) << fitted;  // elided in its middle
  const std::string rest = line.substr(line.find(" 12 triangles"));
  EXPECT_EQ(joined.substr(joined.find(" 12 triangles")), rest) << "nothing else lost: " << fitted;
  EXPECT_EQ(fit_to_width(line, 0), line);
  EXPECT_EQ(fit_to_width("short", 40), "short");
  EXPECT_EQ(elide_middle("abcdefghij", 7), "ab...ij");
}

// ---- under a pseudo-terminal ----------------------------------------------------------------

// Runs tessera with `args` on a terminal `columns` wide and returns all it wrote there.
// `resize_to` > 0: once the first progress line shows, the window is resized to that width.
std::string run_on_terminal(const std::vector<std::string>& args, int columns, int resize_to = 0) {
  winsize size{};
  size.ws_row = 24;
  size.ws_col = static_cast<unsigned short>(columns);
  int master = -1;
  const pid_t pid = ::forkpty(&master, nullptr, nullptr, &size);
  if (pid == 0) {
    std::vector<char*> argv;
    const std::string exe = test::tessera_exe();
    argv.push_back(const_cast<char*>(exe.c_str()));
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(exe.c_str(), argv.data());
    ::_exit(127);
  }
  std::string out;
  char buffer[4096];
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  for (;;) {
    pollfd p{master, POLLIN, 0};
    if (::poll(&p, 1, 100) > 0) {
      const ssize_t n = ::read(master, buffer, sizeof buffer);
      if (n <= 0) break;  // EIO: the program ended and closed the terminal
      out.append(buffer, static_cast<std::size_t>(n));
    }
    if (resize_to > 0 && out.find('%') != std::string::npos) {
      size.ws_col = static_cast<unsigned short>(resize_to);
      ::ioctl(master, TIOCSWINSZ, &size);  // the kernel sends SIGWINCH to the program
      resize_to = 0;
    }
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(pid, SIGKILL);
      break;
    }
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  ::close(master);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << out;
  return out;
}

// What the terminal shows, line by line: each \r or \n starts over, and the erase-line
// sequence takes no column.
std::vector<std::string> screen_lines(std::string out) {
  for (std::size_t at; (at = out.find("\x1b[K")) != std::string::npos;) out.erase(at, 3);
  std::vector<std::string> lines(1);
  for (char c : out) {
    if (c == '\r' || c == '\n') lines.emplace_back();
    else lines.back() += c;
  }
  return lines;
}

// Box.glb copied to a path longer than a narrow terminal.
std::string long_scene_path() {
  const std::string dir = test::make_temp_dir("progress-pty") + "/a-directory-with-a-long-name-for-the-scenes-of-this-test";
  fs::create_directories(dir);
  const std::string scene = dir + "/the-box-scene-with-a-long-file-name.glb";
  fs::copy_file(test::scene_path("khronos/Box/glTF-Binary/Box.glb"), scene, fs::copy_options::overwrite_existing);
  return scene;
}

std::vector<std::string> render_args(const std::string& scene, const std::string& out) {
  return {"render", scene, "--width", "160", "--spp", "100000", "--time-limit", "0.7", "-o", out};
}

class ProgressOnTerminal : public testing::TestWithParam<int> {};

TEST_P(ProgressOnTerminal, NoLineIsWiderThanTheTerminal) {
  const int columns = GetParam();
  const std::string scene = long_scene_path();
  const std::string out = run_on_terminal(render_args(scene, fs::path(scene).parent_path().string() + "/out.exr"), columns);
  int progress = 0;
  for (const std::string& line : screen_lines(out)) {
    EXPECT_LE(line.size(), static_cast<std::size_t>(columns)) << "[" << line << "]\nin:\n" << out;
    progress += line.find("%") != std::string::npos && line.find("ETA") != std::string::npos;
  }
  EXPECT_GE(progress, 2) << "the bar was drawn: " << out;
  EXPECT_NE(out.find("wrote"), std::string::npos) << out;
  if (columns >= 200) {  // room for everything
    EXPECT_NE(out.find("M samples/s"), std::string::npos) << out;
  }
}

INSTANTIATE_TEST_SUITE_P(Widths, ProgressOnTerminal, testing::Values(40, 80, 200));

TEST(ProgressOnTerminal, FollowsAResizedWindow) {
  const std::string scene = long_scene_path();
  const std::string out =
      run_on_terminal(render_args(scene, fs::path(scene).parent_path().string() + "/out.exr"), 200, 40);
  const std::vector<std::string> lines = screen_lines(out);
  // From the end of sampling on (the last bar and the summary), everything fits 40 columns.
  const auto last_bar = std::find_if(lines.rbegin(), lines.rend(), [](const std::string& l) { return l.find("ETA") != std::string::npos; });
  ASSERT_NE(last_bar, lines.rend()) << out;
  for (auto it = lines.rbegin(); it != std::next(last_bar); ++it) EXPECT_LE(it->size(), 40u) << "[" << *it << "]\nin:\n" << out;
}

}  // namespace
}  // namespace tessera
