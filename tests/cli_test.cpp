// The tessera program as a user meets it: exit codes and messages for bad scenes, bad
// options and bad output paths, --help and --version, and what a successful render writes.
// The contract is docs/usage.md ("Exit codes", "Writing files safely", the render options
// table): 0 success; 1 internal failure and, as documented for now, an unusable output path
// (reported before anything is loaded); 2 bad usage or input. Errors are one line
// "tessera: error: ...", and command-line parse errors add one line pointing to --help.
#include <gtest/gtest.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "tests/test_support.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;

const std::string kHelpHint = "Run 'tessera --help' or 'tessera COMMAND --help' for usage.\n";

std::string quote(const std::string& s) { return "'" + s + "'"; }

std::string box() { return test::scene_path("khronos/Box/glTF-Binary/Box.glb"); }

// `tessera ARGS`, bounded by `timeout` so that a hang fails instead of blocking the suite.
test::CommandResult tessera(const std::string& args) {
  return test::run_command("timeout 120 " + quote(test::tessera_exe()) + " " + args);
}

// A tiny, quick render of Box.glb (no camera: the automatic one) to `out`, plus `extra`.
test::CommandResult render_box(const std::string& out, const std::string& extra = "") {
  return tessera("render " + quote(box()) + " --width 16 --spp 1 -q -o " + quote(out) + " " + extra);
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::size_t line_count(const std::string& text) { return std::count(text.begin(), text.end(), '\n'); }

// ---- the scene argument -----------------------------------------------------------------

TEST(CliScene, MissingFileExits2NamingIt) {
  const std::string missing = test::make_temp_dir("cli-missing") + "/no-such-scene.glb";
  const auto r = tessera("render " + quote(missing) + " -q -o " + quote(missing + ".exr"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "tessera: error: " + missing + ": cannot be opened: No such file or directory\n");
  EXPECT_EQ(r.out, "");
}

TEST(CliScene, DirectoryExits2) {
  const std::string dir = test::make_temp_dir("cli-dir-scene");
  const auto r = tessera("info " + quote(dir));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "tessera: error: " + dir + ": is a directory, not a glTF file\n");
}

TEST(CliScene, UnknownSceneNameExits2) {
  const std::string out = test::make_temp_dir("cli-scene") + "/out.exr";
  const auto r = render_box(out, "--scene nosuch");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "tessera: error: " + box() + ": has no scene 'nosuch' (it has 1 scene: 0)\n");
  EXPECT_FALSE(fs::exists(out));
}

TEST(CliScene, CameraIndexBeyondTheScenesCamerasExits2) {
  // cornellBox.gltf has one camera, 'default'.
  const std::string scene = test::scene_path("khronos/CornellBox/glTF/cornellBox.gltf");
  const std::string out = test::make_temp_dir("cli-camera") + "/out.exr";
  const auto r = tessera("render " + quote(scene) + " --width 16 --spp 1 -q --camera 7 -o " + quote(out));
  EXPECT_EQ(r.exit_code, 2);
  ASSERT_EQ(line_count(r.err), 1u) << r.err;
  EXPECT_EQ(r.err.rfind("tessera: error: --camera 7: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("0 'default'"), std::string::npos) << "should list the cameras: " << r.err;
  EXPECT_FALSE(fs::exists(out));
}

// ---- option values ------------------------------------------------------------------------

struct BadOption {
  const char* args;  // appended to a valid tiny render
  const char* option;  // must be named in the message
  const char* value;  // must be quoted back in the message
};

void PrintTo(const BadOption& b, std::ostream* os) { *os << b.args; }

class CliBadOption : public testing::TestWithParam<BadOption> {};

// Values the parser refuses: exit 2, one error line naming the option and the value, then
// the --help hint; nothing is written.
TEST_P(CliBadOption, Exits2NamingOptionAndValue) {
  const std::string out = test::make_temp_dir("cli-bad-option") + "/out.exr";
  const auto r = render_box(out, GetParam().args);
  EXPECT_EQ(r.exit_code, 2);
  const std::string first_line = r.err.substr(0, r.err.find('\n'));
  EXPECT_EQ(first_line.rfind(std::string("tessera: error: ") + GetParam().option, 0), 0u) << r.err;
  EXPECT_NE(first_line.find(GetParam().value), std::string::npos) << r.err;
  EXPECT_EQ(r.err.substr(first_line.size() + 1), kHelpHint);
  EXPECT_FALSE(fs::exists(out));
}

INSTANTIATE_TEST_SUITE_P(Values, CliBadOption,
                         testing::Values(BadOption{"--spp 0", "--spp", "0"},
                                         BadOption{"--spp abc", "--spp", "abc"},
                                         BadOption{"--width -5", "--width", "-5"},
                                         BadOption{"--tile-size 0", "--tile-size", "0"},
                                         BadOption{"--aov bogus", "--aov", "bogus"},
                                         BadOption{"--noise-threshold -1", "--noise-threshold", "-1"},
                                         BadOption{"--noise-threshold 0.01 --min-spp 2", "--min-spp", "2"}),
                         [](const testing::TestParamInfo<BadOption>& info) { return test::identifier(info.param.args); });

TEST(CliOptions, MalformedBackgroundExits2) {
  // Checked after parsing, so no --help hint: one line.
  const std::string out = test::make_temp_dir("cli-background") + "/out.exr";
  const auto r = render_box(out, "--background 1,2");
  EXPECT_EQ(r.exit_code, 2);
  ASSERT_EQ(line_count(r.err), 1u) << r.err;
  EXPECT_EQ(r.err.rfind("tessera: error: --background 1,2: ", 0), 0u) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

// Values the frame's plan reads (--background, --crop) are checked before the scene is read:
// a typo on a large file costs nothing, and is what the user hears of, even when the scene
// path is wrong too.
TEST(CliOptions, MalformedValuesAreRefusedBeforeTheSceneIsRead) {
  const std::string missing = test::make_temp_dir("cli-early-values") + "/no-such-scene.glb";
  for (const char* args : {"--background white", "--crop 0.5,0.2,0,1"}) {
    const auto r = tessera("render " + quote(missing) + " -q " + args);
    EXPECT_EQ(r.exit_code, 2) << args;
    ASSERT_EQ(line_count(r.err), 1u) << r.err;
    const std::string option = std::string(args).substr(0, std::string(args).find(' '));
    EXPECT_EQ(r.err.rfind("tessera: error: " + std::string(args) + ": ", 0), 0u) << r.err;
    EXPECT_EQ(r.err.find("no-such-scene"), std::string::npos) << option << ": " << r.err;
  }
}

TEST(CliOptions, UnknownOptionExits2) {
  const auto r = tessera("render " + quote(box()) + " --bogus-option");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "tessera: error: render: unknown option --bogus-option\n" + kHelpHint);  // nothing near it
}

// ---- output paths: checked before the scene is loaded ---------------------------------

TEST(CliOutput, UnwritableDirectoryIsReportedBeforeRendering) {
  // A render that would take many minutes (2000 px wide, 256 spp); the output path is
  // refused at once.
  const std::string helmet = test::scene_path("khronos/DamagedHelmet/glTF-Binary/DamagedHelmet.glb");
  const auto start = std::chrono::steady_clock::now();
  const auto r = tessera("render " + quote(helmet) + " --width 2000 --spp 256 -o /proc/nope/out.exr");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(r.exit_code, 2);  // bad usage
  EXPECT_EQ(r.err, "tessera: error: /proc/nope/out.exr: directory /proc/nope does not exist\n");
  EXPECT_LT(seconds, 30.0);
}

TEST(CliOutput, OutputIsCheckedBeforeTheSceneIsLoaded) {
  // Both are wrong; the output path is reported, so it was checked first.
  const auto r = tessera("render /no/such/scene.glb -o /proc/nope/out.exr");
  EXPECT_EQ(r.exit_code, 2);  // bad usage
  EXPECT_EQ(r.err, "tessera: error: /proc/nope/out.exr: directory /proc/nope does not exist\n");
}

TEST(CliOutput, ReadOnlyDirectory) {
  if (::geteuid() == 0) GTEST_SKIP() << "root may write into a read-only directory";
  const std::string dir = test::make_temp_dir("cli-read-only");
  fs::permissions(dir, fs::perms::owner_read | fs::perms::owner_exec);
  const auto r = render_box(dir + "/out.exr");
  fs::permissions(dir, fs::perms::owner_all);
  EXPECT_EQ(r.exit_code, 2);  // bad usage
  EXPECT_EQ(r.err, "tessera: error: " + dir + "/out.exr: directory " + dir + " is not writable\n");
}

TEST(CliOutput, MissingDirectory) {
  const std::string out = test::make_temp_dir("cli-missing-dir") + "/not-made/out.exr";
  const auto r = render_box(out);
  EXPECT_EQ(r.exit_code, 2);  // bad usage
  EXPECT_EQ(r.err, "tessera: error: " + out + ": directory " + fs::path(out).parent_path().string() +
                       " does not exist\n");
}

TEST(CliOutput, UnknownExtension) {
  const std::string out = test::make_temp_dir("cli-extension") + "/out.xyz";
  const auto r = render_box(out);
  EXPECT_EQ(r.exit_code, 2);  // bad usage
  ASSERT_EQ(line_count(r.err), 1u) << r.err;
  EXPECT_EQ(r.err.rfind("tessera: error: " + out + ": unknown image format '.xyz'", 0), 0u) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

TEST(CliOutput, FailedRunsLeaveAnExistingOutputUntouched) {
  const std::string dir = test::make_temp_dir("cli-untouched");
  const std::string out = dir + "/frame.exr";
  const std::string bytes = "an earlier frame, not to be replaced\n";
  std::ofstream(out, std::ios::binary) << bytes;
  const std::string malformed = test::data_path("malformed/glb_truncated.glb");
  struct Failure {
    std::string command;
    int exit_code;
  };
  const Failure failures[] = {
      {"render " + quote(box()) + " --width 16 --spp 1 -q --camera 7 -o " + quote(out), 2},  // after loading
      {"render " + quote(box()) + " --width 16 --spp 1 -q --background 1,2 -o " + quote(out), 2},
      {"render " + quote(malformed) + " --width 16 --spp 1 -q -o " + quote(out), 2},
      {"render " + quote(box()) + " --width 16 --spp 1 -q -o " + quote(out) + " --preview /proc/nope/p.png", 2},
  };
  for (const Failure& f : failures) {
    const auto r = tessera(f.command);
    EXPECT_EQ(r.exit_code, f.exit_code) << f.command << "\n" << r.err;
    EXPECT_EQ(read_file(out), bytes) << f.command;
  }
  std::vector<std::string> left;
  for (const auto& entry : fs::directory_iterator(dir)) left.push_back(entry.path().filename().string());
  EXPECT_EQ(left, std::vector<std::string>{"frame.exr"}) << "no temporary files left behind";
}

// ---- a successful render ------------------------------------------------------------------

TEST(CliRender, WritesAValidExrWithItsMetadata) {
  const std::string dir = test::make_temp_dir("cli-render");
  const std::string out = dir + "/box.exr";
  const auto r = tessera("render " + quote(box()) + " --width 16 --height 12 --spp 2 -o " + quote(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "");  // nothing on stdout
  EXPECT_NE(r.err.find("tessera: wrote " + out + "\n"), std::string::npos) << r.err;
  Imf::InputFile file(out.c_str());
  const Imath::Box2i window = file.header().dataWindow();
  EXPECT_EQ(window.max.x - window.min.x + 1, 16);
  EXPECT_EQ(window.max.y - window.min.y + 1, 12);
  const auto* spp = file.header().findTypedAttribute<Imf::IntAttribute>("samplesPerPixel");
  ASSERT_NE(spp, nullptr);
  EXPECT_EQ(spp->value(), 2);
  for (const char* channel : {"R", "G", "B", "A"})
    EXPECT_NE(file.header().channels().findChannel(channel), nullptr) << channel;
}

TEST(CliRender, DefaultOutputIsTheSceneNameInTheCurrentDirectory) {
  const std::string dir = test::make_temp_dir("cli-default-output");
  const auto r = test::run_command("cd " + quote(dir) + " && timeout 120 " + quote(test::tessera_exe()) +
                                   " render " + quote(box()) + " --width 16 --spp 1 -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");  // -q: no progress, no summary, and Box.glb has nothing to warn about
  EXPECT_TRUE(fs::is_regular_file(dir + "/Box.exr"));
}

// ---- help and version -----------------------------------------------------------------------

TEST(CliHelp, TopLevelHelpListsTheCommands) {
  const auto r = tessera("--help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* word : {"render", "info", "bench", "Exit codes"})
    EXPECT_NE(r.out.find(word), std::string::npos) << word;
}

// The long options in the render options table of docs/usage.md.
std::vector<std::string> documented_render_options() {
  std::ifstream doc(test::source_dir() + "/docs/usage.md");
  std::vector<std::string> options;
  bool in_render = false;
  const std::regex option("`(--[a-z-]+)");
  for (std::string line; std::getline(doc, line);) {
    if (line.rfind("## ", 0) == 0) in_render = line == "## tessera render";
    if (!in_render || line.rfind("| `", 0) != 0) continue;
    const std::string first_cell = line.substr(0, line.find('|', 1));
    for (std::sregex_iterator it(first_cell.begin(), first_cell.end(), option), end; it != end; ++it)
      options.push_back((*it)[1]);
  }
  return options;
}

TEST(CliHelp, RenderHelpMentionsEveryDocumentedOption) {
  const std::vector<std::string> options = documented_render_options();
  EXPECT_GE(options.size(), 20u) << "docs/usage.md's render table was not found";
  const auto r = tessera("render --help");
  EXPECT_EQ(r.exit_code, 0);
  for (const std::string& o : options) EXPECT_NE(r.out.find(o), std::string::npos) << o;
  for (const char* short_form : {"-o,--output", "-q,--quiet"})
    EXPECT_NE(r.out.find(short_form), std::string::npos) << short_form;
}

TEST(CliHelp, VersionIsTheProjectVersion) {
  std::ifstream cmake(test::source_dir() + "/CMakeLists.txt");
  std::smatch m;
  std::string version;
  for (std::string line; std::getline(cmake, line);)
    if (std::regex_search(line, m, std::regex(R"(project\(tessera VERSION ([0-9.]+))"))) version = m[1];
  ASSERT_FALSE(version.empty());
  const auto r = tessera("--version");
  EXPECT_EQ(r.exit_code, 0);
  // and the instruction set of the program that ran (tests/isa_dispatch_test.cpp checks which)
  EXPECT_TRUE(std::regex_match(r.out, std::regex("tessera " + version + R"( \(x86-64(-v3)?\)\n)"))) << r.out;
}

}  // namespace
}  // namespace tessera
