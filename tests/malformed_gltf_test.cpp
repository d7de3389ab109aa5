// Every file in tests/data/malformed/ is refused with one exact, single-line message, by
// load_gltf and by `tessera info` (exit 2). expected.tsv holds "file<TAB>problem", the
// problem being the text after "FILE: ". The messages were written to name what is wrong;
// the numbers in them (offsets, lengths, counts, line numbers) were checked by hand against
// the bytes of each file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "scene_io/gltf_loader.h"
#include "scene_io/base/load_error.h"
#include "tests/test_support.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;

struct MalformedCase {
  std::string file, problem;
};

void PrintTo(const MalformedCase& c, std::ostream* os) { *os << c.file; }

std::vector<MalformedCase> read_expected() {
  std::ifstream in(test::data_path("malformed/expected.tsv"));
  std::vector<MalformedCase> cases;
  for (std::string line; std::getline(in, line);) {
    if (line.empty()) continue;
    const std::size_t tab = line.find('\t');
    cases.push_back({line.substr(0, tab), tab == std::string::npos ? "" : line.substr(tab + 1)});
  }
  return cases;
}

std::string case_path(const MalformedCase& c) { return test::data_path("malformed/" + c.file); }

// Files in the directory that are not cases: the table, and data a case refers to.
const std::set<std::string> kNotCases = {"expected.tsv", "short_buffer.bin"};

TEST(MalformedGltfCorpus, ListsEveryFileOnce) {
  const std::vector<MalformedCase> cases = read_expected();
  EXPECT_GE(cases.size(), 25u);
  std::set<std::string> listed;
  for (const MalformedCase& c : cases) {
    EXPECT_TRUE(listed.insert(c.file).second) << c.file << " is listed twice";
    EXPECT_FALSE(c.problem.empty()) << c.file << " has no expected problem";
    EXPECT_TRUE(fs::is_regular_file(case_path(c))) << c.file << " is listed but missing";
  }
  for (const auto& entry : fs::directory_iterator(test::data_path("malformed"))) {
    const std::string name = entry.path().filename().string();
    if (kNotCases.count(name)) continue;
    EXPECT_TRUE(listed.count(name)) << name << " is not in expected.tsv";
  }
}

class MalformedGltf : public testing::TestWithParam<MalformedCase> {};

TEST_P(MalformedGltf, LoaderThrowsTheExpectedProblem) {
  const std::string path = case_path(GetParam());
  try {
    load_gltf(path);
    ADD_FAILURE() << path << " loaded without an error";
  } catch (const SceneLoadError& e) {
    EXPECT_EQ(e.problem(), GetParam().problem);
    EXPECT_EQ(e.file(), path);
  }
}

TEST_P(MalformedGltf, InfoExitsTwoWithOneLine) {
  const std::string path = case_path(GetParam());
  // `timeout` turns a hang into exit 124 instead of a stuck test.
  const test::CommandResult r = test::run_command("timeout 60 " + test::tessera_exe() + " info '" + path + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "tessera: error: " + path + ": " + GetParam().problem + "\n");
  EXPECT_EQ(r.out, "");
}

INSTANTIATE_TEST_SUITE_P(Corpus, MalformedGltf, testing::ValuesIn(read_expected()),
                         [](const testing::TestParamInfo<MalformedCase>& info) { return test::identifier(info.param.file); });

}  // namespace
}  // namespace tessera
