// The render controls a pbrt or Cycles user reaches for (docs/usage.md): --pixel traces one
// pixel and prints its paths, --resolution-scale and --quick, a camera from the command line
// (--look-at, --camera-position/--camera-target), and info --json.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "imageio/image_input.h"
#include "tests/exr_read.h"
#include "tests/test_support.h"

namespace tessera {
namespace {

std::string quote(const std::string& s) { return "'" + s + "'"; }
std::string box() { return test::scene_path("khronos/Box/glTF-Binary/Box.glb"); }

test::CommandResult tessera(const std::string& args) {
  return test::run_command("timeout 60 " + quote(test::tessera_exe()) + " " + args);
}

// ---- --pixel ------------------------------------------------------------------------------

// A Lambertian plane (base colour 0.5, specular 0) over x in [-1, 0], z in [-1, 1] at y = 0,
// lit straight down by a directional light of 2 lux: every point of it sends 0.5 * 2 / pi
// towards any viewer (and nothing else lights the scene under --background 0).
constexpr double kPlaneRadiance = 0.5 * 2.0 / 3.14159265358979323846;

// `place`: the plane's node's translation, as JSON ("[x, y, z]"); none: at the origin.
std::string half_plane_gltf(const std::string& dir, const std::string& place = "") {
  std::vector<std::uint8_t> bin;
  auto put = [&](const void* data, std::size_t n) {
    const auto* b = static_cast<const std::uint8_t*>(data);
    bin.insert(bin.end(), b, b + n);
  };
  const float positions[] = {-1, 0, -1, 0, 0, -1, 0, 0, 1, -1, 0, 1};
  const float normals[] = {0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0};
  const std::uint16_t indices[] = {0, 3, 2, 0, 2, 1};
  put(positions, sizeof positions);
  put(normals, sizeof normals);
  put(indices, sizeof indices);
  const std::string path = dir + "/half-plane.gltf";
  std::ofstream(path) << R"({"asset": {"version": "2.0"},
    "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_specular"],
    "extensions": {"KHR_lights_punctual": {"lights": [{"type": "directional", "intensity": 2}]}},
    "scene": 0, "scenes": [{"nodes": [0, 1]}],
    "nodes": [{"mesh": 0)" + (place.empty() ? "" : ", \"translation\": " + place) + R"(},
              {"rotation": [-0.70710678, 0, 0, 0.70710678], "extensions": {"KHR_lights_punctual": {"light": 0}}}],
    "materials": [{"name": "grey", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1],
                   "metallicFactor": 0, "roughnessFactor": 1},
                   "extensions": {"KHR_materials_specular": {"specularFactor": 0}}}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "material": 0}]}],
    "accessors": [
      {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, 0, -1], "max": [0, 0, 1]},
      {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
      {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 48},
                    {"buffer": 0, "byteOffset": 96, "byteLength": 12}],
    "buffers": [{"byteLength": 108, "uri": "data:application/octet-stream;base64,)"
                      << test::base64(bin) << R"("}]})";
  return path;
}

// Looking straight down at the plane from 2 above the origin; image x runs along +X, so
// column 4 of 9 straddles the plane's edge x = 0.
const std::string kDownView = " --look-at 0,2,0,0,0,0,0,0,-1 --width 9 --height 9 --background 0 --seed 3 ";

struct PrintedSample {
  double radiance = 0.0;  // red
  bool hit = false;
  double x = 0.0, y = 0.0, direct = 0.0;  // of vertex 1
};

std::vector<PrintedSample> printed_samples(const std::string& out) {
  std::vector<PrintedSample> samples;
  const std::regex sample(R"(^sample \d+: radiance \(([-0-9.e]+), )"), vertex(R"(^  vertex 1: position \(([-0-9.e]+), ([-0-9.e]+), )"),
      direct(R"(direct light \(([-0-9.e]+), )");
  std::istringstream lines(out);
  std::smatch m;
  for (std::string line; std::getline(lines, line);) {
    if (std::regex_search(line, m, sample)) samples.push_back({std::stod(m[1])});
    else if (!samples.empty() && std::regex_search(line, m, vertex)) samples.back().hit = true, samples.back().x = std::stod(m[1]), samples.back().y = std::stod(m[2]);
    else if (!samples.empty() && samples.back().hit && samples.back().direct == 0.0 && std::regex_search(line, m, direct)) samples.back().direct = std::stod(m[1]);
  }
  return samples;
}

double printed_mean(const std::string& out) {
  std::smatch m;
  if (!std::regex_search(out, m, std::regex(R"(mean of \d+ samples: \(([-0-9.e]+), )"))) return -1.0;
  return std::stod(m[1]);
}

TEST(CliPixel, PathsOnALitPlaneMatchTheClosedForm) {
  const std::string scene = half_plane_gltf(test::make_temp_dir("cli-pixel-plane"));
  const auto r = tessera("render " + quote(scene) + kDownView + "--spp 16 --pixel 4,4");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  const std::vector<PrintedSample> samples = printed_samples(r.out);
  ASSERT_EQ(samples.size(), 4u) << r.out;  // the first four in full
  EXPECT_NE(r.out.find("(12 more samples not shown)"), std::string::npos) << r.out;
  for (const PrintedSample& s : samples) {
    if (!s.hit) {
      EXPECT_EQ(s.radiance, 0.0) << r.out;  // missed the plane: the black background
      continue;
    }
    EXPECT_NEAR(s.y, 0.0, 1e-5) << r.out;  // on the plane
    EXPECT_LE(s.x, 1e-5) << r.out;  // on its half
    EXPECT_NEAR(std::fabs(s.x), 0.0, 0.25) << r.out;  // near the pixel's centre line x = 0
    EXPECT_NEAR(s.direct, kPlaneRadiance, 1e-5 * kPlaneRadiance) << r.out;  // all of it direct light
    EXPECT_NEAR(s.radiance, kPlaneRadiance, 1e-5 * kPlaneRadiance) << r.out;
  }
  EXPECT_NE(r.out.find("material 0 'grey'"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("sampled diffuse, pdf "), std::string::npos) << r.out;
  // Part of the pixel sees the plane: the mean lies strictly between black and the plane.
  const double mean = printed_mean(r.out);
  EXPECT_GT(mean, 0.05 * kPlaneRadiance) << r.out;
  EXPECT_LT(mean, 0.95 * kPlaneRadiance) << r.out;
}

TEST(CliPixel, MeanIsTheFullRendersPixel) {
  const std::string dir = test::make_temp_dir("cli-pixel-mean");
  const std::string scene = half_plane_gltf(dir), out = dir + "/full.exr";
  const auto full = tessera("render " + quote(scene) + kDownView + "--spp 16 -q -o " + quote(out));
  ASSERT_EQ(full.exit_code, 0) << full.err;
  const std::vector<float> rgb = test::exr_rgb(out);
  for (const int x : {2, 4}) {
    const auto r = tessera("render " + quote(scene) + kDownView + "--spp 16 --pixel " + std::to_string(x) + ",4");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const double pixel = rgb[3 * (4 * 9 + x)];
    EXPECT_NEAR(printed_mean(r.out), pixel, 1e-6 + 1e-5 * pixel) << "pixel " << x << ",4\n" << r.out;
  }
  EXPECT_NEAR(rgb[3 * (4 * 9 + 2)], kPlaneRadiance, 1e-5);  // wholly on the plane
}

// 10,000 units out (for a plane 2 across: rendered about its centre, render_origin.h), the
// paths are printed and the EXR's camera matrix written in world coordinates, and the plane
// still shows exactly its closed form.
TEST(CliPixel, AFarSceneIsReportedInWorldCoordinates) {
  const std::string dir = test::make_temp_dir("cli-pixel-far");
  const std::string scene = half_plane_gltf(dir, "[10000, 0, 0]"), out = dir + "/far.exr";
  const std::string view = " --look-at 10000,2,0,10000,0,0,0,0,-1 --width 9 --height 9 --background 0 --seed 3 --spp 16 ";
  const auto r = tessera("render " + quote(scene) + view + "--pixel 2,4");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  int hits = 0;
  for (const PrintedSample& s : printed_samples(r.out)) {
    ASSERT_TRUE(s.hit) << r.out;  // column 2 lies wholly on the plane
    ++hits;
    EXPECT_NEAR(s.x, 9999.55, 0.2) << r.out;  // world x: the column's centre line is 10000 - 4/9
    EXPECT_NEAR(s.y, 0.0, 1e-3) << r.out;
    EXPECT_NEAR(s.radiance, kPlaneRadiance, 1e-5 * kPlaneRadiance) << r.out;
  }
  EXPECT_EQ(hits, 4) << r.out;
  const auto full = tessera("render " + quote(scene) + view + "-q -o " + quote(out));
  ASSERT_EQ(full.exit_code, 0) << full.err;
  const std::vector<float> m = test::exr_m44f(out, "worldToCamera");  // row vectors: p' = p m
  auto to_camera = [&](float x, float y, float z) {
    return glm::vec3(x * m[0] + y * m[4] + z * m[8] + m[12], x * m[1] + y * m[5] + z * m[9] + m[13],
                     x * m[2] + y * m[6] + z * m[10] + m[14]);
  };
  const glm::vec3 eye = to_camera(10000, 2, 0), target = to_camera(10000, 0, 0);
  EXPECT_NEAR(glm::length(eye), 0.0f, 2e-3f);
  EXPECT_NEAR(target.x, 0.0f, 2e-3f);
  EXPECT_NEAR(target.y, 0.0f, 2e-3f);
  EXPECT_NEAR(target.z, -2.0f, 2e-3f);  // two ahead, down the camera's -z
}

TEST(CliPixel, OutsideTheFrameIsRefused) {
  const auto r = tessera("render " + quote(box()) + " --width 8 --height 4 --pixel 8,0");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "tessera: error: --pixel 8,0: outside the 8x4 frame (X 0 to 7, Y 0 to 3)\n");
  const auto bad = tessera("render " + quote(box()) + " --width 8 --pixel 1");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_EQ(bad.err, "tessera: error: --pixel 1: expected X,Y, two whole numbers (0,0 is the top left pixel)\n");
}

// ---- --resolution-scale and --quick ---------------------------------------------------------

std::array<int, 2> size_of(const std::string& exr) {
  const test::ExrWindows w = test::exr_windows(exr);
  return {w.data[2] - w.data[0] + 1, w.data[3] - w.data[1] + 1};
}

struct SizeCase {
  const char* args;
  int width, height, spp;
};

void PrintTo(const SizeCase& c, std::ostream* os) { *os << c.args; }

class CliResolution : public testing::TestWithParam<SizeCase> {};

TEST_P(CliResolution, SetsTheSizeAndSamples) {
  const SizeCase& c = GetParam();
  const std::string out = test::make_temp_dir("cli-resolution") + "/out.exr";
  const auto r = tessera("render " + quote(box()) + " -q -o " + quote(out) + " " + c.args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(size_of(out), (std::array<int, 2>{c.width, c.height}));
  EXPECT_EQ(test::exr_int(out, "samplesPerPixel"), c.spp);
}

// Box.glb has no camera: 16:9 from the width; the default width is 960.
INSTANTIATE_TEST_SUITE_P(Sizes, CliResolution,
                         testing::Values(SizeCase{"--width 100 --resolution-scale 0.5 --spp 1", 50, 28, 1},  // 100x56 halved
                                         SizeCase{"--width 64 --height 10 --resolution-scale 2 --spp 1", 128, 20, 1},
                                         SizeCase{"--quick", 240, 135, 4},  // 960x540 at 0.25, 4 spp
                                         SizeCase{"--quick --spp 2 --resolution-scale 0.1", 96, 54, 2}),  // given wins
                         [](const testing::TestParamInfo<SizeCase>& info) { return test::identifier(info.param.args); });

// ---- a camera from the command line ---------------------------------------------------------

// The depth (Z) the centre pixel of a 33x33 render of Box.glb (the cube [-0.5, 0.5]^3) sees.
float centre_depth(const std::string& camera_args) {
  const std::string out = test::make_temp_dir("cli-look-at") + "/out.exr";
  const auto r = tessera("render " + quote(box()) + " --width 33 --height 33 --spp 4 --aov depth -q -o " + quote(out) +
                         " " + camera_args);
  EXPECT_EQ(r.exit_code, 0) << camera_args << "\n" << r.err;
  if (r.exit_code != 0) return -1.0f;
  return read_exr_channels(out).channels.at("Z")[16 * 33 + 16];
}

struct CameraCase {
  const char* args;
  float depth;  // at the centre pixel; for a refused view, 0
  const char* message;  // the error line after "tessera: error: ", for a refused view
};

void PrintTo(const CameraCase& c, std::ostream* os) { *os << c.args; }

class CliCamera : public testing::TestWithParam<CameraCase> {};

// The face nearest the eye is 0.5 from the centre: the depth along the view is the rest.
TEST_P(CliCamera, SeesTheObjectAtTheImageCentreOrRefusesADegenerateView) {
  const CameraCase& c = GetParam();
  if (c.message == nullptr) {
    EXPECT_NEAR(centre_depth(c.args), c.depth, 1e-4f);
    return;
  }
  const auto r = tessera("render " + quote(box()) + " --width 8 -q -o /dev/null.exr " + c.args);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, std::string("tessera: error: ") + c.message + "\n");
}

INSTANTIATE_TEST_SUITE_P(
    Views, CliCamera,
    testing::Values(
        CameraCase{"--look-at 3,0,0,0,0,0,0,1,0", 2.5f, nullptr},
        CameraCase{"--look-at 0,4,0,0,0,0,0,0,-1", 3.5f, nullptr},  // from above, up along -Z
        CameraCase{"--look-at 0,0,-6,0,0,0,0,1,0 --fov 10", 5.5f, nullptr},
        CameraCase{"--camera-position 0,0,-6", 5.5f, nullptr},  // looking at the scene's centre
        CameraCase{"--camera-position 5,0,0 --camera-target 0,0,0", 4.5f, nullptr},
        CameraCase{"--look-at 1,1,1,1,1,1,0,1,0", 0.0f,
                   "--look-at: the eye and the target are the same point, so there is no view direction"},
        CameraCase{"--look-at 0,3,0,0,0,0,0,1,0", 0.0f,
                   "--look-at: up (0, 1, 0) is zero or along the view direction; give another up"},
        CameraCase{"--look-at 0,3,0,0,0,0,0,0,0", 0.0f,
                   "--look-at: up (0, 0, 0) is zero or along the view direction; give another up"},
        CameraCase{"--camera-position 0,5,0", 0.0f,
                   "--camera-position: up (0, 1, 0) is zero or along the view direction; give another up"},
        CameraCase{"--look-at 1,2,3", 0.0f, "--look-at 1,2,3: expected EYE,TARGET,UP (9 numbers separated by commas)"},
        CameraCase{"--camera-position 0,0,5 --camera-target 0,x,0", 0.0f,
                   "--camera-target 0,x,0: expected X,Y,Z (3 numbers separated by commas)"}),
    [](const testing::TestParamInfo<CameraCase>& info) { return test::identifier(info.param.args); });

// ---- with --resume FILE alone ---------------------------------------------------------------

TEST(CliCamera, ResumeAloneKeepsTheCommandLineCameraAndScale) {
  const std::string dir = test::make_temp_dir("cli-camera-resume");
  // 256 spp: a frame this small at 16 could finish within the 1 ms limit (24x14 pixels).
  const std::string options = quote(box()) + " --look-at 3,1,2,0,0,0,0,1,0 --width 48 --resolution-scale 0.5 --spp 256 -q ";
  ASSERT_EQ(tessera("render " + options + "-o " + quote(dir + "/full.exr")).exit_code, 0);
  // The first wave always finishes; the time limit stops the render after it.
  ASSERT_EQ(tessera("render " + options + "--time-limit 0.001 -o " + quote(dir + "/part.exr")).exit_code, 0);
  ASSERT_LT(test::exr_int(dir + "/part.exr", "samplesPerPixel"), 256) << "not stopped early";
  const auto resumed = tessera("render --resume " + quote(dir + "/part.exr") + " -q");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_EQ(size_of(dir + "/part.exr"), (std::array<int, 2>{24, 14}));
  EXPECT_EQ(test::exr_rgb(dir + "/part.exr"), test::exr_rgb(dir + "/full.exr"));
}

// ---- info --json ----------------------------------------------------------------------------

TEST(CliInfoJson, BoxFacts) {
  const auto r = tessera("info --json " + quote(box()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["file"], box());
  EXPECT_EQ(j["triangles"]["unique"], 12);  // a cube: 6 faces of 2 triangles
  EXPECT_EQ(j["triangles"]["instanced"], 12);
  EXPECT_EQ(j["meshes"]["count"], 1);
  EXPECT_EQ(j["materials"], 1);
  EXPECT_EQ(j["cameras"].size(), 0u);
  EXPECT_EQ(j["lights"]["punctual"].size(), 0u);
  EXPECT_EQ(j["bounds"]["min"], nlohmann::json({-0.5, -0.5, -0.5}));
  EXPECT_EQ(j["bounds"]["max"], nlohmann::json({0.5, 0.5, 0.5}));
}

TEST(CliInfoJson, CamerasAndLights) {
  const auto cams = tessera("info --json " + quote(test::scene_path("khronos/Cameras/glTF/Cameras.gltf")));
  ASSERT_EQ(cams.exit_code, 0) << cams.err;
  const nlohmann::json c = nlohmann::json::parse(cams.out)["cameras"];
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[0]["projection"], "perspective");
  EXPECT_NEAR(c[0]["yfov_degrees"].get<double>(), 0.7 * 180.0 / 3.14159265358979323846, 1e-4);  // the file's 0.7 rad
  EXPECT_EQ(c[0]["aspect_ratio"], 1.0);
  EXPECT_EQ(c[1]["projection"], "orthographic");
  EXPECT_EQ(c[1]["xmag"], 1.0);
  const std::string scene = half_plane_gltf(test::make_temp_dir("cli-info-json"));
  const auto lit = tessera("info --json " + quote(scene));
  ASSERT_EQ(lit.exit_code, 0) << lit.err;
  const nlohmann::json l = nlohmann::json::parse(lit.out);
  ASSERT_EQ(l["lights"]["punctual"].size(), 1u);
  EXPECT_EQ(l["lights"]["punctual"][0]["type"], "directional");
  EXPECT_EQ(l["lights"]["punctual"][0]["intensity"], 2.0);
  EXPECT_EQ(l["lights"]["punctual"][0]["unit"], "lux");
  EXPECT_EQ(l["extensions"]["used"][0]["name"], "KHR_lights_punctual");
  EXPECT_EQ(l["triangles"]["unique"], 2);
}

}  // namespace
}  // namespace tessera
