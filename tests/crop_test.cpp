// --crop X0,X1,Y0,Y1: a region of the frame, each pixel exactly as in the whole frame, written
// as an EXR whose data window is the region and whose display window is the frame.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tests/exr_read.h"
#include "tests/test_support.h"

namespace tessera {
namespace {

std::string quote(const std::string& s) { return "'" + s + "'"; }

// The Cornell box at 61 x 61 (odd: regions end between tiles), 16 spp, with depth and albedo.
test::CommandResult render(const std::string& out, const std::string& args) {
  return test::run_command("timeout 300 " + quote(test::tessera_exe()) + " render " +
                           quote(test::scene_path("cornell-box/cornell-box.gltf")) +
                           " --width 61 --spp 16 --seed 5 -q --aov albedo,depth -o " + quote(out) + " " + args);
}

// The pixels [x0, x1) x [y0, y1) of a width-wide interleaved RGB image.
std::vector<float> region(const std::vector<float>& rgb, int width, int x0, int x1, int y0, int y1) {
  std::vector<float> out;
  for (int y = y0; y < y1; ++y)
    out.insert(out.end(), rgb.begin() + 3 * (y * width + x0), rgb.begin() + 3 * (y * width + x1));
  return out;
}

TEST(Crop, EveryPixelIsTheWholeFramesAndTheWindowsSayWhere) {
  const std::string dir = test::make_temp_dir("crop");
  ASSERT_EQ(render(dir + "/full.exr", "--tile-size 8").exit_code, 0);
  const std::vector<float> full = test::exr_rgb(dir + "/full.exr");
  // pbrt's rule: pixels ceil(x0 W) to ceil(x1 W) - 1. 0.25 * 61 = 15.25 -> 16; 0.8 * 61 =
  // 48.8 -> 49; 0.5 * 61 = 30.5 -> 31; 1 -> 61. A different tile size and thread count too.
  const auto r = render(dir + "/crop.exr", "--crop 0.25,0.8,0.5,1 --tile-size 32 --threads 1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const test::ExrWindows w = test::exr_windows(dir + "/crop.exr");
  EXPECT_EQ(w.data, (std::array<int, 4>{16, 31, 48, 60}));
  EXPECT_EQ(w.display, (std::array<int, 4>{0, 0, 60, 60}));
  const std::vector<float> crop = test::exr_rgb(dir + "/crop.exr");
  EXPECT_EQ(crop, region(full, 61, 16, 49, 31, 61));  // exactly: float ==, pixel for pixel
  // Two crops that meet at 0.5 tile the frame: together they are the whole frame.
  ASSERT_EQ(render(dir + "/left.exr", "--crop 0,0.5,0,1").exit_code, 0);
  ASSERT_EQ(render(dir + "/right.exr", "--crop 0.5,1,0,1").exit_code, 0);
  EXPECT_EQ(test::exr_windows(dir + "/left.exr").data, (std::array<int, 4>{0, 0, 30, 60}));
  EXPECT_EQ(test::exr_windows(dir + "/right.exr").data, (std::array<int, 4>{31, 0, 60, 60}));
  EXPECT_EQ(test::exr_rgb(dir + "/left.exr"), region(full, 61, 0, 31, 0, 61));
  EXPECT_EQ(test::exr_rgb(dir + "/right.exr"), region(full, 61, 31, 61, 0, 61));
}

TEST(Crop, AnInterruptedCropResumesToTheSameBits) {
  const std::string dir = test::make_temp_dir("crop-resume");
  const std::string crop = "--crop 0.1,0.6,0.2,0.7 ";
  ASSERT_EQ(render(dir + "/whole.exr", crop).exit_code, 0);
  ASSERT_EQ(render(dir + "/part.exr", crop + "--time-limit 0.001").exit_code, 0);
  ASSERT_EQ(test::exr_int(dir + "/part.exr", "partial"), 1) << "not left partial: nothing to test";
  const auto r = render(dir + "/part.exr", crop + "--resume " + quote(dir + "/part.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(test::exr_windows(dir + "/part.exr").data, test::exr_windows(dir + "/whole.exr").data);
  EXPECT_EQ(test::exr_rgb(dir + "/part.exr"), test::exr_rgb(dir + "/whole.exr"));
  // The crop is part of what a resume must match.
  const auto other = render(dir + "/part2.exr", "--resume " + quote(dir + "/whole.exr"));
  EXPECT_EQ(other.exit_code, 2);
}

TEST(Crop, ADenoisedCropKeepsItsWindows) {
  const std::string dir = test::make_temp_dir("crop-denoise");
  ASSERT_EQ(render(dir + "/c.exr", "--crop 0.3,0.9,0,0.5 --aov halves,albedo,normal").exit_code, 0);
  const auto d = test::run_command(quote(test::tessera_exe()) + " denoise -q " + quote(dir + "/c.exr") + " -o " +
                                   quote(dir + "/d.exr"));
  ASSERT_EQ(d.exit_code, 0) << d.err;
  EXPECT_EQ(test::exr_windows(dir + "/d.exr").data, test::exr_windows(dir + "/c.exr").data);
  EXPECT_EQ(test::exr_windows(dir + "/d.exr").display, (std::array<int, 4>{0, 0, 60, 60}));
}

TEST(Crop, RegionsThatAreNotOneAreRefused) {
  const std::string dir = test::make_temp_dir("crop-bad");
  for (const char* bad : {"0.5,0.5,0,1", "0,1,0.7,0.2", "-0.1,0.5,0,1", "0,1.5,0,1", "0,1,0", "a,b,c,d", "0,1,0,1,0"}) {
    const auto r = render(dir + "/x.exr", std::string("--crop ") + bad);
    EXPECT_EQ(r.exit_code, 2) << bad;
    EXPECT_NE(r.err.find("--crop"), std::string::npos) << r.err;
  }
  // 0.2 to 0.21 of 61 pixels: ceil(12.2) = 13 to ceil(12.81) = 13, no pixel.
  const auto empty = render(dir + "/x.exr", "--crop 0.2,0.21,0,1");
  EXPECT_EQ(empty.exit_code, 2);
  EXPECT_NE(empty.err.find("holds no pixel of the 61x61 frame"), std::string::npos) << empty.err;
}

}  // namespace
}  // namespace tessera
