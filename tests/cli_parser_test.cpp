// The parser's messages (docs/usage.md, "Command line"): a number option given text is
// "not a number"; an unknown command or option gets the nearest valid name; `tessera help`
// and `tessera version` work; `render --help` groups its options and ends with examples.
// Errors: exit 2, one line, then the pointer to --help.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "app/cli/nearest_name.h"
#include "tests/test_support.h"

namespace tessera {
namespace {

const std::string kHelpHint = "Run 'tessera --help' or 'tessera COMMAND --help' for usage.\n";

test::CommandResult tessera(const std::string& args) {
  return test::run_command("timeout 60 '" + test::tessera_exe() + "' " + args);
}

std::string box() { return "'" + test::scene_path("khronos/Box/glTF-Binary/Box.glb") + "'"; }

TEST(EditDistance, CountsInsertionsDeletionsSubstitutionsAndSwaps) {
  EXPECT_EQ(edit_distance("widht", "width"), 1);  // one swap of neighbours
  EXPECT_EQ(edit_distance("rendr", "render"), 1);
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3);  // the textbook case
  EXPECT_EQ(edit_distance("", "spp"), 3);
  EXPECT_EQ(edit_distance("same", "same"), 0);
}

TEST(EditDistance, NearestNameOnlyWhenNearEnough) {
  const std::vector<std::string> names = {"--width", "--height", "--spp", "--seed"};
  EXPECT_EQ(nearest_name("--widht", names), "--width");
  EXPECT_EQ(nearest_name("--hieght", names), "--height");
  EXPECT_EQ(nearest_name("--sed", names), "--seed");
  EXPECT_EQ(nearest_name("--bogus-option", names), "");  // nothing is what was meant
}

struct ParseCase {
  const char* args;  // after `tessera`; BOX is replaced by the path of Box.glb
  const char* message;  // the error line after "tessera: error: "
};

void PrintTo(const ParseCase& c, std::ostream* os) { *os << c.args; }

class CliParseError : public testing::TestWithParam<ParseCase> {};

TEST_P(CliParseError, Exits2WithTheMessage) {
  std::string args = GetParam().args;
  if (const std::size_t at = args.find("BOX"); at != std::string::npos) args.replace(at, 3, box());
  const auto r = tessera(args);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, std::string("tessera: error: ") + GetParam().message + "\n" + kHelpHint);
  EXPECT_EQ(r.out, "");
}

INSTANTIATE_TEST_SUITE_P(
    Messages, CliParseError,
    testing::Values(ParseCase{"rendr BOX", "unknown command 'rendr' (did you mean `render`?)"},
                    ParseCase{"ifno BOX", "unknown command 'ifno' (did you mean `info`?)"},
                    ParseCase{"help rendr", "unknown command 'rendr' (did you mean `render`?)"},
                    ParseCase{"frobnicate", "unknown command 'frobnicate'"},
                    ParseCase{"--verison", "unknown option --verison (did you mean `--version`?)"},
                    ParseCase{"render BOX --widht 100", "render: unknown option --widht (did you mean `--width`?)"},
                    ParseCase{"render BOX --sp=4", "render: unknown option --sp (did you mean `--spp`?)"},
                    ParseCase{"info BOX --jsn", "info: unknown option --jsn (did you mean `--json`?)"},
                    ParseCase{"render BOX --spp abc", "--spp: 'abc' is not a number"},
                    ParseCase{"render BOX --spp 2.5", "--spp: '2.5' is not a whole number"},
                    ParseCase{"render BOX --exposure one", "--exposure: 'one' is not a number"},
                    ParseCase{"render BOX --envmap-rotate nan", "--envmap-rotate: 'nan' is not a finite number"},
                    ParseCase{"bench --width 12x", "--width: '12x' is not a number"},
                    ParseCase{"render BOX --spp 0", "--spp: Value 0 not in range 1 to 16777216"},
                    ParseCase{"render BOX --spp 1 --spp 2", "--spp: given more than once"}),
    [](const testing::TestParamInfo<ParseCase>& info) { return test::identifier(info.param.args); });

TEST(CliNoCommand, ListsTheCommands) {
  const auto r = tessera("");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "tessera: error: no command given; the commands are render, info, bench, scaling, denoise, help, "
                   "version\n" + kHelpHint);
}

class CliHelpCommand : public testing::TestWithParam<std::pair<const char*, const char*>> {};

// The command prints what the flag prints, with exit code 0.
TEST_P(CliHelpCommand, PrintsWhatTheFlagPrints) {
  const auto command = tessera(GetParam().first), flag = tessera(GetParam().second);
  EXPECT_EQ(command.exit_code, 0);
  EXPECT_EQ(command.out, flag.out);
  EXPECT_EQ(command.err, "");
  EXPECT_NE(command.out.find("tessera"), std::string::npos) << command.out;
}

INSTANTIATE_TEST_SUITE_P(Commands, CliHelpCommand,
                         testing::Values(std::pair{"help", "--help"}, std::pair{"help render", "render --help"},
                                         std::pair{"help info", "info --help"}, std::pair{"version", "--version"}),
                         [](const testing::TestParamInfo<std::pair<const char*, const char*>>& info) {
                           return test::identifier(info.param.first);
                         });

TEST(CliRenderHelp, GroupsItsOptionsAndEndsWithThreeExamples) {
  const std::string out = tessera("render --help").out;
  // Each group's heading, in this order, with one of its options after it.
  const std::pair<const char*, const char*> groups[] = {
      {"\nOutput:\n", "--preview"},          {"\nSampling:\n", "--noise-threshold"},
      {"\nScene and camera:\n", "--look-at"}, {"\nLights:\n", "--envmap-scale"},
      {"\nTime and resume:\n", "--resume"},  {"\nThreads and profiling:\n", "--stats-json"}};
  std::size_t at = 0;
  for (const auto& [heading, option] : groups) {
    const std::size_t h = out.find(heading, at);
    ASSERT_NE(h, std::string::npos) << heading << " missing or out of order:\n" << out;
    const std::size_t next = out.find(":\n", h + std::string(heading).size());
    const std::size_t o = out.find(option, h);
    EXPECT_LT(o, next) << option << " is not in group " << heading;
    at = h + 1;
  }
  const std::size_t examples = out.find("\nExamples:\n");
  ASSERT_NE(examples, std::string::npos) << out;
  EXPECT_GT(examples, at);
  std::size_t count = 0;
  for (std::size_t p = out.find("\n  tessera render ", examples); p != std::string::npos;
       p = out.find("\n  tessera render ", p + 1))
    ++count;
  EXPECT_EQ(count, 3u) << out.substr(examples);
}

}  // namespace
}  // namespace tessera
