// Options that have no effect with the others given print one warning each, naming the
// option and why, and the render goes on (exit 0); options that contradict each other are
// refused (exit 2) before anything is loaded. docs/usage.md lists them ("Options without
// effect").
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "tests/test_support.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;

std::string quote(const std::string& s) { return "'" + s + "'"; }
std::string box() { return test::scene_path("khronos/Box/glTF-Binary/Box.glb"); }

// A tiny render of Box.glb in `dir` (relative outputs land there) with `args` (1 spp unless
// they say).
test::CommandResult render_in(const std::string& dir, const std::string& args) {
  const std::string spp = args.find("--spp") == std::string::npos ? " --spp 1" : "";
  return test::run_command("cd " + quote(dir) + " && timeout 60 " + quote(test::tessera_exe()) + " render " +
                           quote(box()) + " --width 8 -q" + spp + " " + args);
}

struct Ignored {
  const char* args;
  const char* warnings;  // every line of stderr, each after "tessera: warning: "
};

void PrintTo(const Ignored& c, std::ostream* os) { *os << c.args; }

class CliIgnoredOption : public testing::TestWithParam<Ignored> {};

TEST_P(CliIgnoredOption, WarnsOnceNamingItAndRenders) {
  const std::string dir = test::make_temp_dir("cli-ignored");
  const auto r = render_in(dir, GetParam().args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  std::string expected;
  for (std::string rest = GetParam().warnings; !rest.empty();) {
    const std::size_t end = rest.find('\n');
    expected += "tessera: warning: " + rest.substr(0, end) + "\n";
    rest = end == std::string::npos ? "" : rest.substr(end + 1);
  }
  EXPECT_EQ(r.err, expected);
}

INSTANTIATE_TEST_SUITE_P(
    Warnings, CliIgnoredOption,
    testing::Values(
        Ignored{"-o a.png --aov albedo --half",
                "--aov: layers need an EXR output (-o or --preview FILE.exr); none is written\n"
                "--half: half floats are an EXR option; no EXR is written"},
        Ignored{"-o a.png --owner me --comments 'a test'",
                "--owner: is an EXR header attribute; no EXR is written\n"
                "--comments: is an EXR header attribute; no EXR is written"},
        Ignored{"-o a.exr --exposure 1",
                "--exposure: applies to non-EXR outputs only (the EXR stays scene-linear); add --preview FILE.png"},
        Ignored{"-o a.exr --view-transform standard",
                "--view-transform: applies to display formats (PNG, JPEG, ...) only; none is written"},
        Ignored{"-o a.hdr --preview b.exr --view-transform standard",
                "--view-transform: applies to display formats (PNG, JPEG, ...) only; none is written"},
        Ignored{"-o a.exr --focus-distance 2",
                "--focus-distance: has no effect without --aperture (a pinhole camera is in focus everywhere)"},
        Ignored{"-o a.exr --envmap-scale 2 --envmap-rotate 90",
                "--envmap-scale: has no effect without --envmap\n--envmap-rotate: has no effect without --envmap"},
        Ignored{"-o a.exr --fps 30",
                "--fps: only converts --frame, --frames and --shutter, none of which is given"},
        Ignored{"-o a.exr --motion-steps 5", "--motion-steps: has no effect without --shutter (no motion blur)"},
        Ignored{"-o a.exr --skip-existing", "--skip-existing: applies only with --frames or --frame"},
        Ignored{"-o a.exr --rank-scheduler static", "--rank-scheduler: applies only under mpirun with more than one rank"},
        Ignored{"-o a.exr --pixel 1,1", "--output: has no effect with --pixel, which writes no image"},
        Ignored{"-o a.exr --spp 16 --noise-threshold 0.01",  // Cycles' min spp at 0.01: 64
                "--noise-threshold: no pixel can stop early: each takes 64 samples (its min spp) before it may, and "
                "--spp is 16"},
        Ignored{"-o a.exr --spp 8 --noise-threshold 0.5 --min-spp 8",
                "--noise-threshold: no pixel can stop early: each takes 8 samples (its min spp) before it may, and "
                "--spp is 8"},
        // Given where they act: no warning.
        Ignored{"-o a.exr --preview a.png --aov depth --half --exposure 1 --view-transform standard --aperture 0.1 "
                "--focus-distance 2 --spp 9 --noise-threshold 0.5 --min-spp 8",
                ""}),
    [](const testing::TestParamInfo<Ignored>& info) { return "case" + std::to_string(info.index); });

TEST(CliIgnoredOption, TimeOnASceneWithoutAnimation) {
  const std::string dir = test::make_temp_dir("cli-ignored-time");
  const auto r = render_in(dir, "-o a.exr --time 2");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "tessera: warning: --time: " + box() + " has no animation, so every time shows the same scene\n");
}

TEST(CliIgnoredOption, BackgroundWithAnEnvironmentMap) {
  const std::string dir = test::make_temp_dir("cli-ignored-background");
  const auto r = render_in(dir, "-o a.exr --background 0.5 --envmap " + quote(test::scene_path("env/spruit_sunrise_1k.hdr")));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "tessera: warning: --background: ignored with --envmap (the environment image is the background)\n");
}

struct Conflict {
  const char* args;
  const char* message;  // the error line after "tessera: error: "
};

void PrintTo(const Conflict& c, std::ostream* os) { *os << c.args; }

class CliConflict : public testing::TestWithParam<Conflict> {};

TEST_P(CliConflict, IsRefusedWithExit2BeforeWriting) {
  const std::string dir = test::make_temp_dir("cli-conflict");
  std::ofstream(dir + "/config.ocio") << "not read: the conflict is found first\n";
  const auto r = render_in(dir, GetParam().args);
  EXPECT_EQ(r.exit_code, 2);
  const std::string first_line = r.err.substr(0, r.err.find('\n'));
  EXPECT_EQ(first_line, std::string("tessera: error: ") + GetParam().message);
  EXPECT_FALSE(fs::exists(dir + "/a.exr"));
}

INSTANTIATE_TEST_SUITE_P(
    Refusals, CliConflict,
    testing::Values(
        Conflict{"-o a.exr --preview a.png --view-transform standard --ocio-config config.ocio",
                 "--view-transform and --ocio-config both choose the view of display formats: give one"},
        Conflict{"-o a.exr --preview ./a.exr", "--preview ./a.exr: is the -o file too; give another name"},
        Conflict{"-o a.exr --pixel 1,1 --crop 0,0.5,0,1", "--pixel traces one pixel of one frame: --crop cannot go with it"},
        Conflict{"-o a.exr --pixel 1,1 --frames 1:2", "--pixel traces one pixel of one frame: --frames cannot go with it"},
        Conflict{"-o a.exr --look-at 0,0,5,0,0,0,0,1,0 --camera 0", "--camera excludes --look-at"},
        Conflict{"-o a.exr --camera-position 0,0,5 --look-at 0,0,5,0,0,0,0,1,0", "--look-at excludes --camera-position"}),
    [](const testing::TestParamInfo<Conflict>& info) { return "case" + std::to_string(info.index); });

}  // namespace
}  // namespace tessera
