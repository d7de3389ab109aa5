// Every input in tests/data/fuzz-regressions/ once crashed, hung or tripped a sanitizer in
// scene loading. Loaded the way the fuzzer loads them, each must give a scene or a
// SceneLoadError, nothing else (a crash fails the whole binary; a hang, CTest's timeout).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "scene_io/gltf_loader.h"
#include "scene_io/base/load_error.h"
#include "tests/test_support.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> regression_files() {
  std::vector<std::string> files;
  for (const auto& entry : fs::directory_iterator(test::data_path("fuzz-regressions")))
    if (entry.path().filename() != "README.md") files.push_back(entry.path().filename().string());
  std::sort(files.begin(), files.end());
  return files;
}

class FuzzRegression : public testing::TestWithParam<std::string> {};

TEST_P(FuzzRegression, LoadsOrIsRefusedCleanly) {
  std::ifstream in(test::data_path("fuzz-regressions/" + GetParam()), std::ios::binary);
  const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  try {
    load_gltf_from_memory(bytes, GetParam(), test::data_path(""));
  } catch (const SceneLoadError& e) {
    EXPECT_FALSE(e.problem().empty());
  }
}

TEST(FuzzRegressionCorpus, IsNotEmpty) { EXPECT_FALSE(regression_files().empty()); }

INSTANTIATE_TEST_SUITE_P(Corpus, FuzzRegression, testing::ValuesIn(regression_files()),
                         [](const testing::TestParamInfo<std::string>& info) { return test::identifier(info.param); });

}  // namespace
}  // namespace tessera
