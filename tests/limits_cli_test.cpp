// Absurd and contradictory requests, and a system that fails us: each gets one clear line,
// its documented exit code, and no partial or replaced output file. A full disk is a tiny
// tmpfs mounted for the test (the sandbox and CI run as root; skipped where mounting is not
// allowed), and /dev/full stands for any device given as the output.
#include <gtest/gtest.h>

#include <sys/mount.h>
#include <sys/stat.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "tests/test_support.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;

std::string quote(const std::string& s) { return "'" + s + "'"; }
std::string box() { return test::scene_path("khronos/Box/glTF-Binary/Box.glb"); }

test::CommandResult tessera(const std::string& args, const std::string& env = "") {
  return test::run_command(env + " timeout 120 " + quote(test::tessera_exe()) + " " + args);
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// A 64 KiB file system: a frame of 1000 x 562 pixels does not fit in it, in any format.
class FullDisk : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::make_temp_dir("full-disk");
    if (::mount("tmpfs", dir_.c_str(), "tmpfs", 0, "size=64k") != 0)
      GTEST_SKIP() << "cannot mount a tmpfs here (" << std::strerror(errno) << "): not root?";
    mounted_ = true;
  }
  void TearDown() override {
    if (mounted_) ::umount(dir_.c_str());
  }
  std::string dir_;
  bool mounted_ = false;
};

TEST_F(FullDisk, EveryFormatExits1NamingTheFileAndKeepsTheOldOne) {
  for (const std::string ext : {"exr", "png", "jpg", "hdr", "tif"}) {
    const std::string out = dir_ + "/frame." + ext;
    { std::ofstream(out) << "an older frame"; }
    const auto r = tessera("render " + quote(box()) + " --width 1000 --spp 1 -q -o " + quote(out));
    EXPECT_EQ(r.exit_code, 1) << ext << ": " << r.err;
    EXPECT_EQ(r.err.rfind("tessera: error: " + out + ": ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find("No space left on device"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(read_file(out), "an older frame") << ext;
    for (const auto& entry : fs::directory_iterator(dir_))
      EXPECT_EQ(entry.path().filename().string().rfind(".tessera-tmp-", 0), std::string::npos)
          << ext << ": left " << entry.path();
    fs::remove(out);
  }
}

// A checkpoint that cannot be written is a warning; the render goes on, and the final
// write reports the full disk.
TEST_F(FullDisk, AFailedCheckpointIsAWarningAndTheRenderGoesOn) {
  const std::string out = dir_ + "/frame.exr";
  const auto r = tessera("render " + quote(box()) + " --width 1000 --spp 3 -q --checkpoint 0.001 -o " + quote(out));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("tessera: warning: checkpoint not written: " + out + ": "), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

TEST(Limits, ADeviceAsTheOutputIsRefusedBeforeRendering) {
  const auto r = tessera("render " + quote(box()) + " --width 16 --spp 1 -q -o /dev/full");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "tessera: error: /dev/full: is not a regular file (a device, pipe or socket): tessera writes a "
                   "temporary file beside the output and renames it into place\n");
  struct stat st;
  ASSERT_EQ(::stat("/dev/full", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode)) << "/dev/full was replaced";
}

TEST(Limits, AnImageLargerThanTheMemoryIsRefusedWithTheEstimate) {
  const std::string out = test::make_temp_dir("limits-memory") + "/big.exr";
  // 4096 x 4096 pixels need about 1.3 GiB; say the machine has 1 GB.
  const auto r = tessera("render " + quote(box()) + " --width 4096 --height 4096 -q -o " + quote(out),
                         "TESSERA_MEMORY_AVAILABLE=1000000000");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "tessera: error: this render needs about 1.3 GiB of memory (image 1.3 GiB, textures 0.0 GiB, "
                   "BVH 0.0 GiB, environment 0.0 GiB) but 0.9 GiB is available: use a smaller --width/--height "
                   "or fewer --aov layers\n");
  EXPECT_FALSE(fs::exists(out));
}

TEST(Limits, TheLargestImageWithEveryAovIsRefusedOnThisMachine) {
  // 2^28 pixels with albedo, normal and depth: about 53 GiB, more than a 24 GiB machine has.
  const auto r = tessera("render " + quote(box()) + " --width 16384 --height 16384 --aov albedo,normal,depth -q -o " +
                         quote(test::make_temp_dir("limits-largest") + "/big.exr"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.err.rfind("tessera: error: this render needs about 53.0 GiB of memory", 0), 0u) << r.err;
}

TEST(Limits, AbsurdSizesAreRefusedByTheParser) {
  for (const std::string args : {"--width 200000 --height 200000", "--width -1", "--height 0", "--spp 0",
                                 "--spp -3", "--time-limit 0", "--checkpoint -1", "--tile-size 0"}) {
    const auto r = tessera("render " + quote(box()) + " -q -o /tmp/never-written.exr " + args);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_EQ(r.err.rfind("tessera: error: --", 0), 0u) << args << ": " << r.err;
  }
  EXPECT_FALSE(fs::exists("/tmp/never-written.exr"));
}

TEST(Limits, MoreThan2To28PixelsIsRefused) {
  const auto r = tessera("render " + quote(box()) + " --width 32768 --height 16384 -q -o /tmp/never-written.exr");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "tessera: error: --width 32768 --height 16384: more than 268 million pixels\n");
}

// A tile larger than the image is allowed: the image is one tile, and the same image.
TEST(Limits, ATileLargerThanTheImageIsOneTileAndTheSameImage) {
  const std::string dir = test::make_temp_dir("limits-tile");
  ASSERT_EQ(tessera("render " + quote(box()) + " --width 24 --spp 2 -q --tile-size 4096 -o " + quote(dir + "/a.exr")).exit_code, 0);
  ASSERT_EQ(tessera("render " + quote(box()) + " --width 24 --spp 2 -q --tile-size 5 -o " + quote(dir + "/b.exr")).exit_code, 0);
  // Same pixels: the files differ only in the tileSize and renderTimeSeconds attributes.
  const auto d = test::run_command("idiff -a -fail 0 -failpercent 0 " + quote(dir + "/a.exr") + " " + quote(dir + "/b.exr"));
  EXPECT_EQ(d.exit_code, 0) << d.out << d.err;
}

}  // namespace
}  // namespace tessera
