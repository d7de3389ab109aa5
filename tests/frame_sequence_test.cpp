// Frame sequences (app/frame/frame_sequence.*, tessera render --frames): the numbered names, the
// frames' headers, --skip-existing, and an interrupted sequence continued to the same bits.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>

#include "app/cli/exit_codes.h"
#include "app/frame/frame_sequence.h"
#include "tests/exr_read.h"
#include "tests/test_support.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;

std::string quote(const std::string& s) { return "'" + s + "'"; }

test::CommandResult render(const std::string& args, int spp = 16) {
  const std::string scene = test::scene_path("khronos/BoxAnimated/glTF-Binary/BoxAnimated.glb");
  return test::run_command("timeout 300 " + quote(test::tessera_exe()) + " render " + quote(scene) +
                           " --width 48 --spp " + std::to_string(spp) + " --seed 3 " + args);
}

std::set<std::string> files_in(const std::string& dir) {
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
  return names;
}

TEST(FrameSequence, RangesAndNames) {
  EXPECT_EQ(frame_numbers(parse_frame_range("3:9:3")), (std::vector<int>{3, 6, 9}));
  EXPECT_EQ(frame_numbers(parse_frame_range("1:4")), (std::vector<int>{1, 2, 3, 4}));
  EXPECT_EQ(frame_numbers(parse_frame_range("5:10:4")), (std::vector<int>{5, 9}));
  for (const char* bad : {"", "3", "9:3", "-1:4", "1:4:0", "1:4:x", "1:4:2:1", "a:b"})
    EXPECT_THROW(parse_frame_range(bad), UsageError) << bad;
  EXPECT_EQ(numbered_path("out/shot.####.exr", 7), "out/shot.0007.exr");
  EXPECT_EQ(numbered_path("shot.exr", 7), "shot.0007.exr");
  EXPECT_EQ(numbered_path("a#/take_##_v#.png", 12), "a#/take_12_v12.png");  // only the file name's runs
  EXPECT_EQ(numbered_path("shot.##.exr", 12345), "shot.12345.exr");  // longer numbers are not cut
}

// Exactly the frames asked for, each a complete EXR with its frame number and scene time.
TEST(FrameSequence, WritesExactlyTheNumberedFrames) {
  const std::string dir = test::make_temp_dir("frame-sequence-names");
  const auto r = render("--frames 3:9:3 --fps 12 -q -o " + quote(dir + "/shot.####.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(files_in(dir), (std::set<std::string>{"shot.0003.exr", "shot.0006.exr", "shot.0009.exr"}));
  for (int f : {3, 6, 9}) {
    const std::string path = dir + "/shot.000" + std::to_string(f) + ".exr";
    EXPECT_EQ(test::exr_int(path, "frame"), f);
    EXPECT_FLOAT_EQ(test::exr_float(path, "sceneTime"), f / 12.0f);
    EXPECT_EQ(test::exr_int(path, "partial"), 0);
  }
  // A frame of the sequence is the same frame rendered alone with --frame.
  const auto one = render("--frame 6 --fps 12 -q -o " + quote(dir + "/alone.exr"));
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const std::vector<float> a = test::exr_rgb(dir + "/alone.exr"), b = test::exr_rgb(dir + "/shot.0006.exr");
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0);
}

// BoxAnimated: node 2 (inner_box, 62 triangles) turns under an animated parent, node 3
// (outer_box, 192 triangles) stands still. After the first frame, each frame updates the
// scene built for the one before: only the inner box's BVH is rebuilt; the frames are the
// same as rendered alone (above).
TEST(FrameSequence, LaterFramesRebuildOnlyWhatMoves) {
  const std::string dir = test::make_temp_dir("frame-sequence-update");
  const auto r = render("--frames 0:2 -o " + quote(dir + "/f.#.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto count = [&](const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = r.err.find(what); at != std::string::npos; at = r.err.find(what, at + 1)) ++n;
    return n;
  };
  EXPECT_EQ(count("254 triangles; load"), 3u) << r.err;
  EXPECT_EQ(count("BVH and textures"), 1u) << r.err;
  EXPECT_EQ(count("(62 triangles rebuilt, textures kept)"), 2u) << r.err;
}

// What an interrupted sequence leaves: frames 0 and 1 finished, frame 2 partial (stopped after
// its first sample wave), frame 3 never started; and a stranger file standing for frame 4.
// Rerun with --skip-existing, frames 0, 1 and 4 are kept, 2 continues, 3 renders: every frame
// is then the same bit for bit as in a sequence that ran straight through.
TEST(FrameSequence, AnInterruptedSequenceContinuesToTheSameBits) {
  // 256 spp: frame 2 must outlast the shortest time limit (1 ms) after its first wave; at 16
  // spp, its background pixels summed in closed form, it sometimes did not (CI, ad1b5e6).
  constexpr int kSpp = 256;
  const std::string whole = test::make_temp_dir("frame-sequence-whole"), cut = test::make_temp_dir("frame-sequence-cut");
  ASSERT_EQ(render("--frames 0:3 -q -o " + quote(whole + "/f.#.exr"), kSpp).exit_code, 0);
  ASSERT_EQ(render("--frames 0:1 -q -o " + quote(cut + "/f.#.exr"), kSpp).exit_code, 0);
  ASSERT_EQ(render("--frames 2:2 -q --time-limit 0.001 -o " + quote(cut + "/f.#.exr"), kSpp).exit_code, 0);
  ASSERT_EQ(test::exr_int(cut + "/f.2.exr", "partial"), 1) << "frame 2 was not left partial: nothing to test";
  { std::ofstream(cut + "/f.4.exr") << "not a frame"; }
  const auto before = fs::last_write_time(cut + "/f.0.exr");

  const auto r = render("--frames 0:4 --skip-existing --threads 1 --tile-size 8 -o " + quote(cut + "/f.#.exr"), kSpp);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("frame 0 (1 of 5): " + cut + "/f.0.exr exists, skipped"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("resumed " + cut + "/f.2.exr"), std::string::npos) << r.err;
  EXPECT_EQ(fs::last_write_time(cut + "/f.0.exr"), before);
  std::ifstream stranger(cut + "/f.4.exr");
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(stranger), {}), "not a frame");
  for (int f = 0; f < 4; ++f) {
    const std::string name = "/f." + std::to_string(f) + ".exr";
    EXPECT_EQ(test::exr_int(cut + name, "partial"), 0) << name;
    const std::vector<float> a = test::exr_rgb(whole + name), b = test::exr_rgb(cut + name);
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0) << name;
  }
}

// --shutter end to end on a skinned mesh without normals (CesiumMan): the frame renders, its
// header gives the shutter in scene seconds, and the blur changes the image.
TEST(FrameSequence, ShutterBlursASkinAndRecordsTheShutter) {
  const std::string dir = test::make_temp_dir("frame-sequence-shutter");
  const std::string scene = test::scene_path("khronos/CesiumMan/glTF-Binary/CesiumMan.glb");
  const std::string base = quote(test::tessera_exe()) + " render " + quote(scene) + " --width 32 --spp 4 -q --frame 20 ";
  auto r = test::run_command(base + "--shutter -1,1 -o " + quote(dir + "/blur.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FLOAT_EQ(test::exr_float(dir + "/blur.exr", "shutterOpen"), 19.0f / 24.0f);
  EXPECT_FLOAT_EQ(test::exr_float(dir + "/blur.exr", "shutterClose"), 21.0f / 24.0f);
  r = test::run_command(base + "-o " + quote(dir + "/still.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(test::exr_rgb(dir + "/blur.exr"), test::exr_rgb(dir + "/still.exr"));
  r = test::run_command(base + "--shutter 0.5,0.5 -o " + quote(dir + "/closed.exr"));  // no time: no blur
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(test::exr_rgb(dir + "/closed.exr"), test::exr_rgb(dir + "/still.exr"));
}

// A camera sliding from x = 0 to x = 2 over the first second: at frame 12 (0.5 s) under a
// shutter from -0.5 to 0.5 frames, the header's camera is where it is at the frame's time,
// x = 1 (the opening would put it at 23/24), in Imath's row-vector layout (translation last).
TEST(FrameSequence, TheHeadersCameraIsAtTheFramesTimeInsideTheShutter) {
  const std::string dir = test::make_temp_dir("frame-sequence-camera");
  std::ofstream(dir + "/cam.gltf") << R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}],
    "nodes": [{"camera": 0, "translation": [0, 0, 5]}],
    "cameras": [{"type": "perspective", "perspective": {"yfov": 0.7, "znear": 0.1}}],
    "buffers": [{"byteLength": 32, "uri": "data:application/octet-stream;base64,AAAAAAAAgD8AAAAAAAAAAAAAoEAAAABAAAAAAAAAoEA="}],
    "bufferViews": [{"buffer": 0, "byteLength": 8}, {"buffer": 0, "byteOffset": 8, "byteLength": 24}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 2, "type": "SCALAR", "min": [0], "max": [1]},
                  {"bufferView": 1, "componentType": 5126, "count": 2, "type": "VEC3"}],
    "animations": [{"samplers": [{"input": 0, "output": 1}], "channels": [{"sampler": 0, "target": {"node": 0, "path": "translation"}}]}]})";
  for (const char* shutter : {"-0.5,0.5", "0,0", "-1,0"}) {
    const auto r = test::run_command(quote(test::tessera_exe()) + " render " + quote(dir + "/cam.gltf") +
                                     " --frame 12 --width 16 --spp 1 -q --shutter " + shutter + " -o " + quote(dir + "/c.exr"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::vector<float> m = test::exr_m44f(dir + "/c.exr", "worldToCamera");
    EXPECT_NEAR(m[12], -1.0f, 1e-5f) << shutter;
    EXPECT_NEAR(m[14], -5.0f, 1e-5f) << shutter;
  }
}

TEST(FrameSequence, BadRangesAndCombinationsAreRefused) {
  const std::string dir = test::make_temp_dir("frame-sequence-bad");
  auto r = render("--frames 5:2 -o " + quote(dir + "/f.#.exr"));
  EXPECT_EQ(r.exit_code, kExitBadInput);
  EXPECT_NE(r.err.find("--frames 5:2: expected FIRST:LAST"), std::string::npos) << r.err;
  r = render("--frames 1:2 --time 3 -o " + quote(dir + "/f.#.exr"));
  EXPECT_EQ(r.exit_code, kExitBadInput) << r.err;
  r = render("--frames 1:2 --shutter 0.5,0.25 -o " + quote(dir + "/f.#.exr"));
  EXPECT_EQ(r.exit_code, kExitBadInput);
  EXPECT_NE(r.err.find("--shutter 0.5,0.25: expected OPEN,CLOSE"), std::string::npos) << r.err;
  EXPECT_TRUE(files_in(dir).empty());
}

}  // namespace
}  // namespace tessera
