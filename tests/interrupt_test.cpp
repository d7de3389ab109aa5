// SIGINT/SIGTERM during a render: the first keeps every finished sample and writes a
// complete image marked partial (exit 130); a second exits at once and leaves the earlier
// output untouched.
#include <gtest/gtest.h>

#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfIntAttribute.h>

#include <filesystem>
#include <fstream>

#include "tests/exr_read.h"
#include "tests/test_support.h"

namespace tessera {
namespace {

// Starts a render that would take hours, sends `signals` once it runs, waits. Tiles are
// large (1024 px) by default so that the tiles in flight take a while to finish after a
// first signal. SIGTERM because a background
// job of a shell script starts with SIGINT ignored, and tessera leaves it so. Start-up
// takes most of a second on a loaded machine: a signal before the handler is installed
// kills tessera (143), and one before the first wave ends leaves nothing to write; then try
// again, waiting longer.
test::CommandResult interrupted_render(const std::string& out, const std::string& signals,
                                       const std::string& size = "--width 2000 --tile-size 1024") {
  const std::string scene = test::scene_path("cornell-box/cornell-box.gltf");
  test::CommandResult r;
  for (int wait : {1, 3, 6}) {
    // The signals must reach tessera itself (not a wrapper such as timeout(1), which passes
    // on only the first); a watchdog kills it after a minute if a signal is lost.
    r = test::run_command("'" + test::tessera_exe() + "' render '" + scene + "' -o '" + out + "' " + size +
                          " --spp 1000000 --threads 2 & pid=$!; (sleep 60; kill -KILL $pid 2>/dev/null) & dog=$!; sleep " +
                          std::to_string(wait) + "; " + signals + " wait $pid; rc=$?; kill $dog 2>/dev/null; exit $rc");
    if (r.exit_code != 143 && r.err.find("not written") == std::string::npos) break;
  }
  return r;
}

TEST(Interrupt, FirstSignalWritesTheFinishedSamplesAndExits130) {
  const std::string out = test::make_temp_dir("interrupt-first") + "/frame.exr";
  const test::CommandResult r = interrupted_render(out, "kill -TERM $pid;", "--width 200 --tile-size 32");
  EXPECT_EQ(r.exit_code, 130) << r.err;
  ASSERT_TRUE(std::filesystem::exists(out)) << r.err;
  EXPECT_EQ(test::exr_int(out, "partial"), 1);
  const int spp = test::exr_int(out, "samplesPerPixel");
  EXPECT_GT(spp, 0);
  EXPECT_LT(spp, 1000000);
  EXPECT_NE(r.err.find("interrupted at " + std::to_string(spp) + " spp"), std::string::npos) << r.err;
}

TEST(Interrupt, SecondSignalExitsAtOnceAndKeepsTheOldFile) {
  const std::string dir = test::make_temp_dir("interrupt-second");
  const std::string out = dir + "/frame.exr";
  { std::ofstream(out) << "an older frame"; }
  // Two signals pending together merge into one: a pause keeps them apart even when the
  // process is not scheduled for a while. The one tile in flight (a whole 3000 px image,
  // several seconds a sample per pixel) takes longer than that to finish.
  const test::CommandResult r =
      interrupted_render(out, "kill -TERM $pid; sleep 1; kill -TERM $pid;", "--width 3000 --tile-size 4096");
  EXPECT_EQ(r.exit_code, 130) << r.err;
  std::ifstream in(out);
  std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_TRUE(content == "an older frame") << "the output was replaced (" << content.size() << " bytes)";
  EXPECT_NE(r.err.find("interrupted again"), std::string::npos) << r.err;
}

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

std::vector<std::string> temporary_files(const std::string& dir) {
  std::vector<std::string> found;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    if (entry.path().filename().string().rfind(".tessera-tmp-", 0) == 0) found.push_back(entry.path().string());
  return found;
}

// A finished frame at -o: what a render interrupted over it must leave byte for byte.
std::string finished_frame(const std::string& dir) {
  const std::string out = dir + "/frame.exr";
  const test::CommandResult r = test::run_command("'" + test::tessera_exe() + "' render '" +
                                                  test::scene_path("cornell-box/cornell-box.gltf") + "' -o '" + out +
                                                  "' --width 16 --spp 2 -q");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return out;
}

TEST(Interrupt, OverAFinishedFrameThePartialGoesBesideIt) {
  const std::string dir = test::make_temp_dir("interrupt-finished");
  const std::string out = finished_frame(dir), before = file_bytes(out);
  const test::CommandResult r = interrupted_render(out, "kill -TERM $pid;", "--width 200 --tile-size 32");
  EXPECT_EQ(r.exit_code, 130) << r.err;
  EXPECT_TRUE(file_bytes(out) == before) << "the finished frame was replaced";
  const std::string partial = dir + "/frame.partial.exr";
  ASSERT_TRUE(std::filesystem::exists(partial)) << r.err;
  EXPECT_EQ(test::exr_int(partial, "partial"), 1);
  EXPECT_NE(r.err.find(out + " holds a finished frame, kept; the partial frame goes beside it (continue it with "
                             "--resume " + partial + ")"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("wrote " + partial), std::string::npos) << r.err;
  EXPECT_TRUE(temporary_files(dir).empty());
}

// Any partial frame (here one stopped by its time limit) goes beside a finished one; resumed
// to the end, it becomes the finished frame at -o (the same bits as one straight render), and
// the partial file goes.
TEST(Interrupt, APartialBesideAFinishedFrameResumesIntoIt) {
  const std::string dir = test::make_temp_dir("interrupt-resume-beside");
  const std::string out = finished_frame(dir), before = file_bytes(out);
  const std::string partial = dir + "/frame.partial.exr", straight = dir + "/straight.exr";
  const std::string render = "'" + test::tessera_exe() + "' render '" + test::scene_path("cornell-box/cornell-box.gltf") +
                             "' --width 24 --spp 24 --seed 5 -q -o ";
  ASSERT_EQ(test::run_command(render + "'" + straight + "'").exit_code, 0);
  test::CommandResult r = test::run_command(render + "'" + out + "' --time-limit 0.001");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(file_bytes(out) == before) << "the finished frame was replaced";
  ASSERT_EQ(test::exr_int(partial, "partial"), 1);
  r = test::run_command("'" + test::tessera_exe() + "' render --resume '" + partial + "' -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(test::exr_int(out, "partial"), 0);
  EXPECT_TRUE(test::exr_rgb(out) == test::exr_rgb(straight));
  EXPECT_FALSE(std::filesystem::exists(partial));
  EXPECT_TRUE(temporary_files(dir).empty());
}

// The second signal lands while a checkpoint is being written (the render checkpoints after
// every wave; the signals wait for its temporary file): the process ends at once, and the
// temporary file goes with it; the finished frame stays, the earlier checkpoint beside it.
TEST(Interrupt, ASecondSignalDuringAWriteLeavesNoTemporaryFile) {
  const std::string dir = test::make_temp_dir("interrupt-second-write");
  const std::string out = finished_frame(dir), before = file_bytes(out);
  const std::string partial = dir + "/frame.partial.exr";
  const std::string writing = "ls -a '" + dir + "' | grep -q '^.tessera-tmp-'";
  test::CommandResult r;
  for (int attempt = 0; attempt < 3; ++attempt) {  // two signals merged into one: again
    r = interrupted_render(out,
                           "until [ -f '" + partial + "' ]; do sleep 0.01; done; until " + writing +
                               "; do :; done; kill -TERM $pid; sleep 0.02; kill -TERM $pid;",
                           "--width 500 --tile-size 64 --checkpoint 0.001");
    if (r.err.find("interrupted again") != std::string::npos) break;
  }
  EXPECT_EQ(r.exit_code, 130) << r.err;
  EXPECT_NE(r.err.find("interrupted again"), std::string::npos) << r.err;
  EXPECT_TRUE(file_bytes(out) == before) << "the finished frame was replaced";
  EXPECT_EQ(test::exr_int(partial, "partial"), 1);
  EXPECT_EQ(temporary_files(dir), std::vector<std::string>{});
}

}  // namespace
}  // namespace tessera
