// tessera render --time-limit, --checkpoint and --resume from the command line: a render
// stopped by its time limit and resumed (with other threads and tiles) writes the same
// pixels as one that ran straight through; checkpoints are resumable while the render
// runs; a mismatched scene or setting, or a file that cannot be resumed, exits 2.
#include <gtest/gtest.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFloatAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfMultiPartInputFile.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <thread>

#include "tests/exr_read.h"
#include "tests/test_support.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;

std::string quote(const std::string& s) { return "'" + s + "'"; }

const std::string kSettings = " --width 40 --spp 40 --max-bounces 4 --seed 7 -q";

test::CommandResult render(const std::string& scene, const std::string& args) {
  return test::run_command("timeout 300 " + quote(test::tessera_exe()) + " render " + quote(scene) + " " + args);
}

std::string cornell() { return test::scene_path("cornell-box/cornell-box.gltf"); }

// One FLOAT channel, e.g. the per-pixel counts `spp`.
std::vector<float> channel_of(const std::string& path, const std::string& name) {
  Imf::InputFile file(path.c_str());
  const Imath::Box2i dw = file.header().dataWindow();
  const int w = dw.max.x + 1, h = dw.max.y + 1;
  std::vector<float> px(static_cast<std::size_t>(w) * h, -1.0f);
  Imf::FrameBuffer fb;
  fb.insert(name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(px.data()), sizeof(float), sizeof(float) * w));
  file.setFrameBuffer(fb);
  file.readPixels(0, h - 1);
  return px;
}

// The resume data lives in the second part of the file (the first holds the frame alone).
bool has_resume_data(const std::string& path) {
  Imf::MultiPartInputFile file(path.c_str());
  return file.parts() == 2 && file.header(1).findTypedAttribute<Imf::StringAttribute>("tesseraResume") &&
         file.header(1).channels().findChannel("tessera.samples");
}

TEST(ResumeCli, TimeLimitedThenResumedIsTheSameBitForBit) {
  const std::string dir = test::make_temp_dir("resume-cli");
  auto r = render(cornell(), "-o " + quote(dir + "/whole.exr") + kSettings);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(has_resume_data(dir + "/whole.exr"));  // a finished frame is a plain frame

  // The first wave always finishes; a limit of a millisecond stops right after it.
  r = render(cornell(), "-o " + quote(dir + "/part.exr") + kSettings + " --time-limit 0.001");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(test::exr_int(dir + "/part.exr", "partial"), 1);
  EXPECT_EQ(test::exr_int(dir + "/part.exr", "targetSamplesPerPixel"), 40);
  EXPECT_LT(test::exr_int(dir + "/part.exr", "samplesPerPixel"), 40);
  EXPECT_TRUE(has_resume_data(dir + "/part.exr"));

  r = render(cornell(), "--resume " + quote(dir + "/part.exr") + " -o " + quote(dir + "/resumed.exr") + kSettings +
                            " --threads 1 --tile-size 13");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(test::exr_int(dir + "/resumed.exr", "partial"), 0);
  EXPECT_EQ(test::exr_int(dir + "/resumed.exr", "samplesPerPixel"), 40);
  const std::vector<float> whole = test::exr_rgb(dir + "/whole.exr"), resumed = test::exr_rgb(dir + "/resumed.exr");
  ASSERT_EQ(whole.size(), resumed.size());
  EXPECT_EQ(std::memcmp(whole.data(), resumed.data(), whole.size() * sizeof(float)), 0);
}

TEST(ResumeCli, ResumeRewritesTheFileItContinuesByDefault) {
  const std::string dir = test::make_temp_dir("resume-cli-default");
  const std::string part = dir + "/frame.exr";
  ASSERT_EQ(render(cornell(), "-o " + quote(part) + kSettings + " --time-limit 0.001").exit_code, 0);
  const auto r = test::run_command("cd " + quote(dir) + " && " + quote(test::tessera_exe()) + " render " +
                                   quote(cornell()) + " --resume frame.exr" + kSettings);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(test::exr_int(part, "partial"), 0);
  EXPECT_EQ(test::exr_int(part, "samplesPerPixel"), 40);
}

class ResumeMismatch : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::make_temp_dir("resume-mismatch");
    part_ = dir_ + "/part.exr";
    const auto r = render(cornell(), "-o " + quote(part_) + kSettings + " --time-limit 0.001");
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  test::CommandResult resume(const std::string& scene, const std::string& args) {
    return render(scene, "--resume " + quote(part_) + " -o " + quote(dir_ + "/out.exr") + " " + args);
  }
  // Each option given with the file's settings: refused (exit 2) with the message.
  template <std::size_t N>
  void expect_refused(const std::pair<std::string, std::string> (&cases)[N]) {
    for (const auto& [args, message] : cases) {
      const auto r = resume(cornell(), args + " -q");  // the others: the file's
      EXPECT_EQ(r.exit_code, 2) << args;
      EXPECT_NE(r.err.find(message), std::string::npos) << args << ": " << r.err;
    }
  }
  std::string dir_, part_;
};

// --spp may raise the target (the file's samples are the first ones of the longer render),
// never lower it.
TEST_F(ResumeMismatch, ALowerSppIsRefusedAHigherOneRaisesTheTarget) {
  auto r = resume(cornell(), "--spp 39 -q");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "tessera: error: --resume " + part_ +
                       ": --spp 39 contradicts the file, rendered with --spp 40 (--spp may only raise the target); "
                       "leave it out to continue as it was started\n");
  EXPECT_FALSE(fs::exists(dir_ + "/out.exr"));
  r = resume(cornell(), "--spp 41 -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(test::exr_int(dir_ + "/out.exr", "samplesPerPixel"), 41);
  // The partial stopped after the first wave, which a 41-spp render shares: the same bits.
  ASSERT_EQ(render(cornell(), "-o " + quote(dir_ + "/straight.exr") + " --width 40 --spp 41 --max-bounces 4 --seed 7 -q")
                .exit_code, 0);
  const std::vector<float> straight = test::exr_rgb(dir_ + "/straight.exr"), raised = test::exr_rgb(dir_ + "/out.exr");
  ASSERT_EQ(straight.size(), raised.size());
  EXPECT_EQ(std::memcmp(straight.data(), raised.data(), straight.size() * sizeof(float)), 0);
}

// An option given that contradicts the file is named, with the value the file has.
TEST_F(ResumeMismatch, AnotherSeedSizeOrCameraIsRefused) {
  const std::pair<std::string, std::string> cases[] = {
      {"--seed 8", "--seed 8 contradicts the file, rendered with --seed 7"},
      {"--width 41", "--width 41 contradicts the file, rendered with --width 40"},
      {"--fov 30", "--fov 30 contradicts the file, rendered without --fov"},
      {"--background 1", "--background 1 contradicts the file, rendered with --background auto"}};
  expect_refused(cases);
}

// Settings that change what a sample adds: the pixel filter, light sampling and clamping.
TEST_F(ResumeMismatch, AnotherPixelFilterLightSamplingOrClampIsRefused) {
  const std::pair<std::string, std::string> cases[] = {
      {"--pixel-filter box", "--pixel-filter box contradicts the file, rendered with --pixel-filter blackman-harris"},
      {"--filter-width 2", "--filter-width 2 contradicts the file, rendered without --filter-width"},
      {"--light-sampling bsdf", "--light-sampling bsdf contradicts the file, rendered with --light-sampling mis"},
      {"--clamp 10", "--clamp 10 contradicts the file, rendered without --clamp"}};
  expect_refused(cases);
}

TEST_F(ResumeMismatch, AnotherSceneFileIsRefused) {
  // The same scene with one more byte: another file, however alike.
  fs::copy_file(test::scene_path("cornell-box/cornell-box.bin"), dir_ + "/cornell-box.bin");
  fs::copy_file(cornell(), dir_ + "/cornell-box.gltf");
  std::ofstream(dir_ + "/cornell-box.gltf", std::ios::app) << "\n";
  const auto r = resume(dir_ + "/cornell-box.gltf", kSettings);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("tessera: error: --resume " + part_ + ": was rendered from another scene file"),
            std::string::npos) << r.err;
}

TEST_F(ResumeMismatch, OtherThreadsTilesAndExposureAreAllowed) {
  const auto r = resume(cornell(), kSettings + " --threads 1 --tile-size 64 --scheduler chunks --half --exposure 1");
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST(ResumeCli, AFinishedFrameIsRefused) {
  const std::string dir = test::make_temp_dir("resume-finished");
  ASSERT_EQ(render(cornell(), "-o " + quote(dir + "/done.exr") + kSettings).exit_code, 0);
  const auto r = render(cornell(), "--resume " + quote(dir + "/done.exr") + kSettings);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "tessera: error: " + dir + "/done.exr: is a finished render: nothing to resume\n");
}

TEST(ResumeCli, AFileThatIsNotAnExrIsRefusedBeforeLoading) {
  const std::string dir = test::make_temp_dir("resume-not-exr");
  std::ofstream(dir + "/frame.exr") << "not an image";
  const auto r = render("/no/such/scene.gltf", "--resume " + quote(dir + "/frame.exr"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err.rfind("tessera: error: " + dir + "/frame.exr: cannot be read for resuming: ", 0), 0u) << r.err;
}

// A render killed outright (SIGKILL: no chance to write) still leaves its last checkpoint,
// which resumes.
TEST(ResumeCli, ACheckpointSurvivesAKillAndResumes) {
  const std::string dir = test::make_temp_dir("checkpoint-kill");
  const std::string out = dir + "/frame.exr";
  const std::string long_render = " --width 32 --spp 1000000 --seed 3 -q";
  const auto r = test::run_command(quote(test::tessera_exe()) + " render " + quote(cornell()) + " -o " + quote(out) +
                                   long_render + " --checkpoint 0.2 & pid=$!; for i in $(seq 600); do [ -f " +
                                   quote(out) + " ] && break; sleep 0.1; done; sleep 0.5; kill -KILL $pid; wait $pid");
  EXPECT_EQ(r.exit_code, 137) << r.err;
  ASSERT_TRUE(fs::exists(out)) << r.err;
  EXPECT_EQ(test::exr_int(out, "partial"), 1);
  EXPECT_TRUE(has_resume_data(out));
  const int spp = test::exr_int(out, "samplesPerPixel");
  const auto resumed = render(cornell(), "--resume " + quote(out) + long_render + " --time-limit 0.5");
  EXPECT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_GT(test::exr_int(out, "samplesPerPixel"), spp);
}

// Adaptive sampling stopped by its time limit (after the first wave), resumed with other
// threads and tiles: the same pixels and per-pixel counts as one run straight through.
// (Stops after later waves, with convergence flags stored: AdaptiveResume.*.)
const std::string kAdaptive = kSettings + " --noise-threshold 0.05 --min-spp 8 --aov halves";

TEST(ResumeCli, AdaptiveTimeLimitedThenResumedIsTheSameBitForBit) {
  const std::string dir = test::make_temp_dir("resume-cli-adaptive");
  auto r = render(cornell(), "-o " + quote(dir + "/whole.exr") + kAdaptive);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = render(cornell(), "-o " + quote(dir + "/part.exr") + kAdaptive + " --time-limit 0.001");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(test::exr_int(dir + "/part.exr", "partial"), 1);
  r = render(cornell(), "--resume " + quote(dir + "/part.exr") + " -o " + quote(dir + "/resumed.exr") + kAdaptive +
                            " --threads 1 --tile-size 7");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(test::exr_int(dir + "/resumed.exr", "partial"), 0);
  for (const char* layer : {"R", "G", "B", "even.R", "odd.G", "spp"}) {
    const std::vector<float> whole = channel_of(dir + "/whole.exr", layer), resumed = channel_of(dir + "/resumed.exr", layer);
    EXPECT_EQ(std::memcmp(whole.data(), resumed.data(), whole.size() * sizeof(float)), 0) << layer;
  }
}

// The EXR of an adaptive render: each pixel's count in `spp` (at least the minimum, at most
// --spp, the fewest is samplesPerPixel), the threshold and minimum in the header; the
// summary says how many pixels converged.
TEST(AdaptiveCli, TheExrRecordsCountsAndThresholdAndTheSummaryTheConvergedShare) {
  const std::string dir = test::make_temp_dir("adaptive-cli");
  const std::string out = dir + "/frame.exr";
  const auto r = render(cornell(), "-o " + quote(out) + " --width 40 --spp 64 --seed 7 --noise-threshold 0.05 --min-spp 8");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  Imf::InputFile file(out.c_str());
  EXPECT_FLOAT_EQ(file.header().typedAttribute<Imf::FloatAttribute>("noiseThreshold").value(), 0.05f);
  EXPECT_EQ(test::exr_int(out, "minSamplesPerPixel"), 8);
  EXPECT_EQ(test::exr_int(out, "partial"), 0);
  EXPECT_EQ(file.header().channels().findChannel("even.R"), nullptr);  // halves only when asked for
  const std::vector<float> spp = channel_of(out, "spp");
  const float fewest = *std::min_element(spp.begin(), spp.end());
  EXPECT_EQ(fewest, static_cast<float>(test::exr_int(out, "samplesPerPixel")));
  EXPECT_EQ(fewest, 8.0f);  // the walls are smooth enough to stop at the minimum
  EXPECT_EQ(*std::max_element(spp.begin(), spp.end()), 64.0f);  // the noisiest need everything
  const long converged = std::count_if(spp.begin(), spp.end(), [](float n) { return n < 64.0f; });
  const std::size_t at = r.err.find("% of pixels converged");
  ASSERT_NE(at, std::string::npos) << r.err;
  const double printed = std::stod(r.err.substr(r.err.rfind(' ', at) + 1));
  EXPECT_NEAR(printed, 100.0 * converged / spp.size(), 0.5) << r.err;
}

TEST(ResumeCli, AnotherNoiseThresholdIsRefusedNoneGivenIsTheFiles) {
  const std::string dir = test::make_temp_dir("resume-cli-adaptive-mismatch");
  const std::string part = dir + "/part.exr";
  ASSERT_EQ(render(cornell(), "-o " + quote(part) + kAdaptive + " --time-limit 0.001").exit_code, 0);
  auto r = render(cornell(), "--resume " + quote(part) + " -o " + quote(dir + "/out.exr") + kSettings +
                                 " --noise-threshold 0.1 --min-spp 8 --aov halves");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--noise-threshold 0.1 contradicts the file, rendered with --noise-threshold 0.05"),
            std::string::npos) << r.err;
  // Left out, the threshold, minimum and AOVs are the file's: the adaptive render goes on.
  r = render(cornell(), "--resume " + quote(part) + " -o " + quote(dir + "/out.exr") + kSettings);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FLOAT_EQ(test::exr_float(dir + "/out.exr", "noiseThreshold"), 0.05f);
  EXPECT_EQ(test::exr_int(dir + "/out.exr", "minSamplesPerPixel"), 8);
}

}  // namespace
}  // namespace tessera
