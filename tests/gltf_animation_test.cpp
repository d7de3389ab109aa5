// glTF animations (scene_io/nodes/gltf_animation.*): the specification's interpolation formulas
// computed by hand on small channels, and the loader posing InterpolationTest's nodes.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <glm/gtc/quaternion.hpp>

#include <OpenEXR/ImfFloatAttribute.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfIntAttribute.h>

#include "imageio/image_input.h"
#include "scene_io/nodes/gltf_animation.h"
#include "scene_io/gltf_loader.h"
#include "scene_io/base/load_error.h"
#include "tests/test_support.h"

namespace tessera {
namespace {

AnimationChannel channel(AnimationPath path, Interpolation mode, std::vector<float> times, std::vector<float> values) {
  AnimationChannel c;
  c.node = 0;
  c.path = path;
  c.interpolation = mode;
  c.times = std::move(times);
  c.values = std::move(values);
  c.width = path == AnimationPath::Rotation ? 4 : 3;
  return c;
}

TEST(GltfAnimation, StepHoldsThePreviousKey) {
  const AnimationChannel c = channel(AnimationPath::Translation, Interpolation::Step, {1, 2, 4}, {0, 0, 0, 1, 2, 3, 5, 5, 5});
  EXPECT_EQ(sample_channel(c, 1.99f), std::vector<float>({0, 0, 0}));
  EXPECT_EQ(sample_channel(c, 2.0f), std::vector<float>({1, 2, 3}));
  EXPECT_EQ(sample_channel(c, 3.9f), std::vector<float>({1, 2, 3}));
  EXPECT_EQ(sample_channel(c, 0.0f), std::vector<float>({0, 0, 0}));  // before the first key: the first
  EXPECT_EQ(sample_channel(c, 9.0f), std::vector<float>({5, 5, 5}));  // after the last: the last
}

TEST(GltfAnimation, LinearInterpolatesBetweenKeys) {
  const AnimationChannel c = channel(AnimationPath::Scale, Interpolation::Linear, {0, 2}, {1, 1, 1, 3, 5, -1});
  const std::vector<float> v = sample_channel(c, 0.5f);  // u = 1/4
  EXPECT_FLOAT_EQ(v[0], 1.5f);
  EXPECT_FLOAT_EQ(v[1], 2.0f);
  EXPECT_FLOAT_EQ(v[2], 0.5f);
}

// Rotations: spherical linear interpolation, the shorter way. From identity to 90 degrees
// about z, a quarter of the way is 22.5 degrees (a lerp of the quaternions would give 22.2).
TEST(GltfAnimation, LinearRotationIsSlerpTheShortWay) {
  const float h = std::sqrt(0.5f);  // (x, y, z, w) of 90 degrees about z: (0, 0, h, h)
  AnimationChannel c = channel(AnimationPath::Rotation, Interpolation::Linear, {0, 1}, {0, 0, 0, 1, 0, 0, h, h});
  std::vector<float> q = sample_channel(c, 0.25f);
  EXPECT_NEAR(q[2], std::sin(glm::radians(22.5f) / 2), 1e-6f);
  EXPECT_NEAR(q[3], std::cos(glm::radians(22.5f) / 2), 1e-6f);
  // The same rotation stored as -q: still the 90-degree arc, not the 270-degree one.
  c.values = {0, 0, 0, 1, 0, 0, -h, -h};
  q = sample_channel(c, 0.25f);
  const float angle = 2.0f * std::acos(std::fabs(q[3]));
  EXPECT_NEAR(glm::degrees(angle), 22.5f, 1e-3f);
}

// CUBICSPLINE (Appendix C): p(t) = (2u^3 - 3u^2 + 1) v0 + td (u^3 - 2u^2 + u) b0 + (-2u^3 + 3u^2) v1
// + td (u^3 - u^2) a1, with b0 the first key's out-tangent and a1 the second's in-tangent.
TEST(GltfAnimation, CubicSplineIsTheSpecificationsHermite) {
  // keys at 1 and 3 (td = 2): in-tangent, value, out-tangent per key, 3 floats each.
  const AnimationChannel c =
      channel(AnimationPath::Translation, Interpolation::CubicSpline, {1, 3},
              {9, 9, 9, /*v0*/ 0, 1, 2, /*b0*/ 1, 0, -1, /*a1*/ 2, 2, 2, /*v1*/ 4, 1, 0, 9, 9, 9});
  const float u = 0.5f, td = 2.0f;  // time 2
  const float h00 = 2 * u * u * u - 3 * u * u + 1, h10 = u * u * u - 2 * u * u + u, h01 = -2 * u * u * u + 3 * u * u,
              h11 = u * u * u - u * u;
  const float v0[3] = {0, 1, 2}, b0[3] = {1, 0, -1}, a1[3] = {2, 2, 2}, v1[3] = {4, 1, 0};
  const std::vector<float> v = sample_channel(c, 2.0f);
  for (int i = 0; i < 3; ++i) EXPECT_FLOAT_EQ(v[i], h00 * v0[i] + h10 * td * b0[i] + h01 * v1[i] + h11 * td * a1[i]);
  EXPECT_EQ(sample_channel(c, 1.0f), std::vector<float>({0, 1, 2}));  // the keys' values, not the tangents
  EXPECT_EQ(sample_channel(c, 3.0f), std::vector<float>({4, 1, 0}));
}

GltfLoadResult load_interpolation_test(float time, const std::string& animation = "") {
  GltfLoadParams p;
  p.animation = animation;
  p.time = time;
  return load_gltf(test::scene_path("khronos/InterpolationTest/glTF-Binary/InterpolationTest.glb"), p);
}

const Instance& instance_named(const SceneDescription& s, const std::string& name) {
  for (const Instance& i : s.instances)
    if (i.node_name == name) return i;
  throw std::runtime_error("no instance " + name);
}

// InterpolationTest: "Linear Translation" moves node Cube.009 (a root, so its world transform
// is its local one) between its keys; at a key it sits exactly at the key's value, and between
// two keys at their linear mix, read from the file's own keys.
TEST(GltfAnimation, InterpolationTestNodesArePlacedByTheirKeys) {
  const GltfLoadResult at0 = load_interpolation_test(0.0f);
  ASSERT_EQ(at0.animations.size(), 9u);
  const Animation* linear = nullptr;
  for (const Animation& a : at0.animations)
    if (a.name == "Linear Translation") linear = &a;
  ASSERT_NE(linear, nullptr);
  const AnimationChannel& c = linear->channels.at(0);
  ASSERT_GE(c.times.size(), 3u);
  const float t1 = c.times[1], t2 = c.times[2], mid = 0.3f * t1 + 0.7f * t2;
  const std::string node = "Cube.009";
  const glm::vec3 at_key = glm::vec3(instance_named(load_interpolation_test(t1).scene, node).object_to_world[3]);
  for (int i = 0; i < 3; ++i) EXPECT_FLOAT_EQ(at_key[i], c.values[3 + i]);
  const glm::vec3 between = glm::vec3(instance_named(load_interpolation_test(mid).scene, node).object_to_world[3]);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(between[i], 0.3f * c.values[3 + i] + 0.7f * c.values[6 + i], 1e-5f);
  // --animation none: the file's rest pose, whatever the time.
  const GltfLoadResult rest = load_interpolation_test(mid, "none");
  EXPECT_TRUE(rest.playing.empty());
  const glm::vec3 stored = glm::vec3(instance_named(rest.scene, node).object_to_world[3]);
  EXPECT_NEAR(stored.x, -3.2975807f, 1e-6f);  // the node's own translation in the file
  // Only "Step Translation": Cube.009 keeps its rest pose, Cube.008 moves.
  const GltfLoadResult step = load_interpolation_test(mid, "Step Translation");
  ASSERT_EQ(step.playing.size(), 1u);
  EXPECT_NEAR(instance_named(step.scene, node).object_to_world[3].x, -3.2975807f, 1e-6f);
}

TEST(GltfAnimation, AnUnknownAnimationIsRefusedListingTheFilesOnes) {
  try {
    load_interpolation_test(0.0f, "Bounce");
    ADD_FAILURE() << "loaded";
  } catch (const SceneLoadError& e) {
    EXPECT_NE(e.problem().find("has no animation 'Bounce' (it has 9 animations: 0 'Step Scale', 1 'Linear Scale'"),
              std::string::npos)
        << e.problem();
  }
  EXPECT_EQ(load_interpolation_test(0.0f, "4").playing, std::vector<int>({4}));
}

}  // namespace
}  // namespace tessera

// ---- the command line ----------------------------------------------------------------------

namespace tessera {
namespace {

test::CommandResult tessera_cli(const std::string& args) {
  return test::run_command("timeout 120 '" + test::tessera_exe() + "' " + args);
}

// --frame 12 at --fps 24 is time 0.5: the same image as --time 0.5, and the header says so.
TEST(GltfAnimationCli, FrameIsTimeTimesFpsAndTheHeaderRecordsIt) {
  const std::string dir = test::make_temp_dir("animation-cli");
  const std::string scene = "'" + test::scene_path("khronos/BoxAnimated/glTF-Binary/BoxAnimated.glb") + "'";
  const std::string common = " --width 32 --spp 2 -q --threads 1";
  ASSERT_EQ(tessera_cli("render " + scene + common + " --frame 12 -o " + dir + "/f12.exr").exit_code, 0);
  ASSERT_EQ(tessera_cli("render " + scene + common + " --time 0.5 -o " + dir + "/t05.exr").exit_code, 0);
  ASSERT_EQ(tessera_cli("render " + scene + common + " -o " + dir + "/t0.exr").exit_code, 0);
  const FrameImage f12 = read_frame_exr(dir + "/f12.exr"), t05 = read_frame_exr(dir + "/t05.exr"), t0 = read_frame_exr(dir + "/t0.exr");
  EXPECT_EQ(f12.rgb, t05.rgb);
  EXPECT_NE(f12.rgb, t0.rgb);  // the box has moved
  Imf::InputFile file((dir + "/f12.exr").c_str());
  const auto* time = file.header().findTypedAttribute<Imf::FloatAttribute>("sceneTime");
  const auto* frame = file.header().findTypedAttribute<Imf::IntAttribute>("frame");
  ASSERT_NE(time, nullptr);
  ASSERT_NE(frame, nullptr);
  EXPECT_FLOAT_EQ(time->value(), 0.5f);
  EXPECT_EQ(frame->value(), 12);
  const auto both = tessera_cli("render " + scene + common + " --frame 1 --time 2 -o " + dir + "/x.exr");
  EXPECT_EQ(both.exit_code, 2);  // bad usage
  EXPECT_NE(both.err.find("excludes"), std::string::npos) << both.err;
}

}  // namespace
}  // namespace tessera

// ---- morph targets -------------------------------------------------------------------------

namespace tessera {
namespace {

// SimpleMorph: one triangle, base (0,0,0) (1,0,0) (0.5,0.5,0); target 0 moves the third vertex
// by (-1, 1, 0), target 1 by (1, 1, 0) (the file's accessors 2 and 3). The third vertex is
// (0.5 - w0 + w1, 0.5 + w0 + w1, 0) for weights (w0, w1).
glm::vec3 third_vertex(const SceneDescription& s) { return s.meshes.at(s.instances.at(0).mesh).primitives.at(0).positions.at(2); }

std::string simple_morph_with(const std::string& weights_json, const std::string& where) {
  const std::string dir = test::make_temp_dir("simple-morph");
  const std::string src = test::scene_path("khronos/SimpleMorph/glTF/");
  for (const char* f : {"simpleMorphGeometry.bin", "simpleMorphAnimation.bin"})
    std::filesystem::copy_file(src + f, dir + "/" + f);
  std::ifstream in(src + "SimpleMorph.gltf");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // The mesh's default weights "[0.5, 0.5]" replaced, or the node given its own.
  const std::size_t at = text.find("\"weights\"");
  const std::size_t open = text.find('[', at), close = text.find(']', open);
  if (where == "mesh") text.replace(open, close - open + 1, weights_json);
  if (where == "node") {
    const std::size_t node = text.find("\"mesh\"", text.find("\"nodes\""));
    text.insert(node, "\"weights\" : " + weights_json + ", ");
  }
  std::ofstream(dir + "/m.gltf") << text;
  return dir + "/m.gltf";
}

TEST(GltfMorph, WeightsZeroOneAndHalfGiveBaseTargetAndMidpoint) {
  GltfLoadParams still;
  still.animation = "none";  // the weights the file gives, not the animation's
  const std::pair<std::string, glm::vec3> cases[] = {
      {"[0, 0]", {0.5f, 0.5f, 0.0f}}, {"[1, 0]", {-0.5f, 1.5f, 0.0f}}, {"[0.5, 0]", {0.0f, 1.0f, 0.0f}},
      {"[0, 1]", {1.5f, 1.5f, 0.0f}}, {"[0.5, 0.5]", {0.5f, 1.5f, 0.0f}}};
  for (const auto& [weights, expected] : cases) {
    const glm::vec3 v = third_vertex(load_gltf(simple_morph_with(weights, "mesh"), still).scene);
    for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(v[c], expected[c]) << "mesh weights " << weights;
  }
  // The node's weights override the mesh's (the file's mesh keeps [0.5, 0.5]).
  const glm::vec3 v = third_vertex(load_gltf(simple_morph_with("[1, 0]", "node"), still).scene);
  EXPECT_FLOAT_EQ(v.x, -0.5f);
  EXPECT_FLOAT_EQ(v.y, 1.5f);
}

// The animation drives the weights: at each key the vertex is where that key's weights put it.
TEST(GltfMorph, AnimatedWeightsMoveTheVertex) {
  const std::string path = test::scene_path("khronos/SimpleMorph/glTF/SimpleMorph.gltf");
  const GltfLoadResult r = load_gltf(path);
  const AnimationChannel& c = r.animations.at(0).channels.at(0);
  ASSERT_EQ(c.path, AnimationPath::Weights);
  ASSERT_EQ(c.width, 2);
  for (std::size_t k = 0; k < c.times.size(); ++k) {
    GltfLoadParams p;
    p.time = c.times[k];
    const glm::vec3 v = third_vertex(load_gltf(path, p).scene);
    const float w0 = c.values[2 * k], w1 = c.values[2 * k + 1];
    EXPECT_FLOAT_EQ(v.x, 0.5f - w0 + w1) << "key " << k;
    EXPECT_FLOAT_EQ(v.y, 0.5f + w0 + w1) << "key " << k;
  }
}

}  // namespace
}  // namespace tessera

namespace tessera {
namespace {

// Motion blur's description: with 3 motion steps over a shutter, a moving node's placement,
// a skinned mesh's vertices and the shutter are those of the scene posed at each step's time
// (open, middle, close); what stands still gets no motion.
TEST(GltfMotionSteps, EachStepIsTheSceneAtItsTime) {
  const std::string box = test::scene_path("khronos/BoxAnimated/glTF-Binary/BoxAnimated.glb");
  GltfLoadParams params{"", "", "", 1.0f};
  params.shutter_open = -0.25f, params.shutter_close = 0.25f, params.motion_steps = 3;
  const SceneDescription blurred = load_gltf(box, params).scene;
  EXPECT_EQ(blurred.motion_steps, 3);
  EXPECT_FLOAT_EQ(blurred.shutter_open, 0.75f);
  EXPECT_FLOAT_EQ(blurred.shutter_close, 1.25f);
  const float times[3] = {0.75f, 1.0f, 1.25f};
  int moving = 0;
  for (std::size_t i = 0; i < blurred.instances.size(); ++i) {
    const Instance& inst = blurred.instances[i];
    moving += !inst.motion.empty();
    for (int k = 0; k < 3; ++k) {
      const Instance posed = load_gltf(box, {"", "", "", times[k]}).scene.instances.at(i);
      EXPECT_EQ(k == 0 ? inst.object_to_world : inst.motion.empty() ? inst.object_to_world : inst.motion[k - 1],
                posed.object_to_world) << "instance " << i << " step " << k;
    }
  }
  EXPECT_GT(moving, 0);
  EXPECT_LT(moving, static_cast<int>(blurred.instances.size()));  // the inner box stands still

  const std::string skin = test::scene_path("khronos/SimpleSkin/glTF/SimpleSkin.gltf");
  GltfLoadParams skin_params{"", "", "", 0.5f};
  skin_params.shutter_close = 0.5f, skin_params.motion_steps = 2;
  const SceneDescription bent = load_gltf(skin, skin_params).scene;
  const TriangleMesh& m = bent.meshes.at(0).primitives.at(0);
  ASSERT_EQ(m.motion_positions.size(), 1u);
  EXPECT_TRUE(m.motion_normals.empty() && m.motion_tangents.empty());  // it has neither
  EXPECT_EQ(m.positions, load_gltf(skin, {"", "", "", 0.5f}).scene.meshes[0].primitives[0].positions);
  EXPECT_EQ(m.motion_positions[0], load_gltf(skin, {"", "", "", 1.0f}).scene.meshes[0].primitives[0].positions);
  // The bounds hold every step: the tip (-0.5, 2) turned 45 degrees about (0, 1) reaches
  // x = -0.5 cos 45 - sin 45 = -1.0607, further out than at 90 degrees (-1).
  EXPECT_NEAR(bent.bounds.lo.x, -0.5f * std::cos(0.7854f) - std::sin(0.7854f), 2e-3f);
}

// A point light on a node that slides from (0, 2, 0) to (1, 2, 0) over one second: with a
// shutter over the second half, its position at the opening and its node's transform at the
// closing; without a shutter, where the node is at the frame's time and no motion.
TEST(GltfMotionSteps, LightsFollowTheirNodesOverTheShutter) {
  const std::string json = R"({
    "asset": {"version": "2.0"}, "extensionsUsed": ["KHR_lights_punctual"],
    "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "intensity": 3}]}},
    "scenes": [{"nodes": [0]}],
    "nodes": [{"extensions": {"KHR_lights_punctual": {"light": 0}}}],
    "buffers": [{"byteLength": 32, "uri": "data:application/octet-stream;base64,AAAAAAAAgD8AAAAAAAAAQAAAAAAAAIA/AAAAQAAAAAA="}],
    "bufferViews": [{"buffer": 0, "byteLength": 8}, {"buffer": 0, "byteOffset": 8, "byteLength": 24}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 2, "type": "SCALAR", "min": [0], "max": [1]},
                  {"bufferView": 1, "componentType": 5126, "count": 2, "type": "VEC3"}],
    "animations": [{"samplers": [{"input": 0, "output": 1}], "channels": [{"sampler": 0, "target": {"node": 0, "path": "translation"}}]}]
  })";
  const std::vector<std::uint8_t> bytes(json.begin(), json.end());
  GltfLoadParams params{"", "", "", 0.5f};
  params.shutter_close = 0.5f, params.motion_steps = 2;
  const SceneDescription blurred = load_gltf_from_memory(bytes, "light.gltf", ".", params).scene;
  ASSERT_EQ(blurred.lights.size(), 1u);
  const PunctualLight& light = blurred.lights[0];
  EXPECT_EQ(light.position, glm::vec3(0.5f, 2.0f, 0.0f));
  ASSERT_EQ(light.motion.size(), 1u);
  EXPECT_EQ(glm::vec3(light.motion[0][3]), glm::vec3(1.0f, 2.0f, 0.0f));
  EXPECT_TRUE(blurred.animated);
  const SceneDescription still = load_gltf_from_memory(bytes, "light.gltf", ".", {"", "", "", 0.25f}).scene;
  EXPECT_EQ(still.lights.at(0).position, glm::vec3(0.25f, 2.0f, 0.0f));
  EXPECT_TRUE(still.lights[0].motion.empty());
  EXPECT_FALSE(load_gltf_from_memory(bytes, "light.gltf", ".", {"", "", "none", 0.25f}).scene.animated);
}

}  // namespace
}  // namespace tessera
