// RenderScene::update: the next frame of an animated scene takes over the scene already built,
// rebuilding only the BVHs of what moved, and renders exactly what a scene built fresh from
// that frame's description renders.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "renderer/render/render.h"
#include "tests/same_bits.h"
#include "tests/scene_builders.h"

namespace tessera {
namespace {

glm::mat4 translate(glm::vec3 t) { return glm::translate(glm::mat4(1.0f), t); }

// A room at time t: a static floor, wall and dense sphere; a lamp that slides along x with t;
// a small sphere placed twice, its first placement rising with t; a quad that turns about y
// with t (mirrored from t = 1 on: its baked copy reverses its winding). Built animated.
constexpr int kStaticSphereSubdivisions = 4;  // 20 * 4^4 = 5120 triangles, never rebuilt
SceneDescription room_at(float t, float small_sphere_radius = 0.15f) {
  SceneDescription d;
  d.animated = true;
  const int white = test::add_material(d, test::diffuse(vec3(0.7f)));
  const int red = test::add_material(d, test::diffuse(vec3(0.7f, 0.1f, 0.1f)));
  const int lamp = test::add_material(d, test::emitter(vec3(6.0f)));
  test::add_mesh(d, test::make_quad({0, -1, 0}, {1, 0, 0}, {0, 0, -1}, white));  // floor, facing up
  test::add_mesh(d, test::make_quad({0, 0, -1}, {1, 0, 0}, {0, 1, 0}, white));  // back wall
  test::add_mesh(d, test::make_sphere({0.4f, -0.6f, 0.0f}, 0.35f, kStaticSphereSubdivisions, red));
  test::add_mesh(d, test::make_quad({0, 0.8f, 0}, {0.25f, 0, 0}, {0, 0, 0.25f}, lamp), {translate({0.3f * t, 0, 0})});
  test::add_mesh(d, test::make_sphere({0, 0, 0}, small_sphere_radius, 1, white),
                 {translate({-0.5f, -0.8f + 0.2f * t, 0.3f}), translate({-0.2f, -0.8f, -0.4f})});
  const glm::mat4 turn = glm::rotate(glm::mat4(1.0f), 0.6f * t, glm::vec3(0, 1, 0));
  const glm::mat4 mirror = t >= 1.0f ? glm::scale(glm::mat4(1.0f), {-1, 1, 1}) : glm::mat4(1.0f);
  test::add_mesh(d, test::make_quad({0, 0, 0}, {0.2f, 0, 0}, {0, 0.2f, 0}, white),
                 {translate({-0.3f, 0.1f, 0.2f}) * turn * mirror});
  return d;
}

constexpr std::uint64_t kLampTriangles = 2, kTurningQuadTriangles = 2;

FrameImage render(const RenderScene& scene, const vec3& at = vec3(0.0f)) {
  RenderSettings s;
  s.width = 40;
  s.height = 30;
  s.spp = 8;
  s.max_bounces = 6;
  s.threads = 2;
  s.seed = 7;
  s.aovs = {true, true, true};
  const Camera look = test::look_at(at + vec3(0, 0, 3), at + vec3(0, -0.2f, 0), 45.0f);
  const RenderCamera cam = scene.camera(look, s.width, s.height, {});
  return render_frame(scene, cam, s).image;
}

EnvironmentParams grey() {
  EnvironmentParams env;
  env.background = vec3(0.1f);
  return env;
}

TEST(SceneUpdate, RebuildsOnlyWhatMovedAndRendersAsAFreshBuild) {
  RenderScene scene(room_at(0.0f), grey());
  const FrameImage first = render(scene);
  for (float t : {0.5f, 1.5f}) {  // 1.5: the turning quad is mirrored now
    SceneDescription next = room_at(t);
    ASSERT_TRUE(scene.update(next));
    // The lamp and the turning quad are baked into world space: their BVHs are rebuilt. The
    // rising sphere is an instance: only its transform changes. The rest is kept.
    EXPECT_EQ(scene.rebuilt_triangles, kLampTriangles + kTurningQuadTriangles);
    const FrameImage updated = render(scene);
    const RenderScene fresh(room_at(t), grey());
    test::expect_same_image(updated, render(fresh));
    EXPECT_FALSE(test::same_bits(updated.rgb, first.rgb));  // the update did change the image
  }
}

// The room moved to `at`, placements and bounds.
SceneDescription room_at(float t, const vec3& at) {
  SceneDescription d = room_at(t);
  for (Instance& instance : d.instances) instance.object_to_world = translate(at) * instance.object_to_world;
  d.bounds = {d.bounds.lo + at, d.bounds.hi + at};
  return d;
}

// 10,000 units out the room (2 across) is rendered about the corner of its 16-unit grid
// nearest its centre (renderer/geometry/render_origin.h): an update that leaves that corner the
// nearest renders as a fresh build of the frame; one that moves the room nearer another
// corner is refused (a fresh build, with that corner as its origin, follows).
TEST(SceneUpdate, AFarAnimationKeepsItsRenderOriginUntilItNearsAnotherCorner) {
  const vec3 far(1e4f, 0.0f, 0.0f), farther = far + vec3(9.0f, 0.0f, 0.0f);
  RenderScene scene(room_at(0.0f, far), grey());
  EXPECT_EQ(scene.origin, far);
  SceneDescription next = room_at(0.5f, far);
  ASSERT_TRUE(scene.update(next));
  EXPECT_EQ(scene.origin, far);
  const RenderScene fresh(room_at(0.5f, far), grey());
  test::expect_same_image(render(scene, far), render(fresh, far));
  SceneDescription away = room_at(0.5f, farther);
  EXPECT_FALSE(scene.update(away));
  EXPECT_EQ(RenderScene(room_at(0.5f, farther), grey()).origin, vec3(10016.0f, 0.0f, 0.0f));
}

TEST(SceneUpdate, AnInstancedMeshThatChangesShapeIsRebuiltOnce) {
  RenderScene scene(room_at(0.0f), grey());
  SceneDescription next = room_at(0.0f, 0.2f);  // the twice-placed sphere grows; nothing moves
  ASSERT_TRUE(scene.update(next));
  const std::uint64_t small_sphere = 20 * 4;  // one subdivision, built once for both placements
  EXPECT_EQ(scene.rebuilt_triangles, small_sphere);
  test::expect_same_image(render(scene), render(RenderScene(room_at(0.0f, 0.2f), grey())));
}

TEST(SceneUpdate, NothingChangedRebuildsNothing) {
  RenderScene scene(room_at(0.25f), grey());
  const FrameImage before = render(scene);
  SceneDescription same = room_at(0.25f);
  ASSERT_TRUE(scene.update(same));
  EXPECT_EQ(scene.rebuilt_triangles, 0u);
  test::expect_same_image(render(scene), before);
}

TEST(SceneUpdate, AnotherStructureIsRefusedAndLeftUntouched) {
  RenderScene scene(room_at(0.0f), grey());
  auto refused = [&](SceneDescription next, const char* why) {
    const SceneDescription copy = next;
    EXPECT_FALSE(scene.update(next)) << why;
    EXPECT_EQ(next.meshes.size(), copy.meshes.size()) << why;
    for (std::size_t m = 0; m < next.meshes.size(); ++m)
      for (std::size_t p = 0; p < next.meshes[m].primitives.size(); ++p)
        EXPECT_EQ(next.meshes[m].primitives[p].positions, copy.meshes[m].primitives[p].positions) << why;
  };
  SceneDescription more = room_at(0.5f);
  test::add_mesh(more, test::make_quad({0, 0, 0.5f}, {0.1f, 0, 0}, {0, 0.1f, 0}, 0));
  refused(more, "a mesh more");
  SceneDescription finer = room_at(0.5f);
  finer.meshes[2].primitives[0] = test::make_sphere({0.4f, -0.6f, 0.0f}, 0.35f, 3, 1);
  refused(finer, "other triangles");
  SceneDescription other_material = room_at(0.5f);
  other_material.meshes[0].primitives[0].material = 1;
  refused(other_material, "another material");
  SceneDescription still = room_at(0.5f);
  still.animated = false;
  refused(still, "not animated: built for quality, not for updates");
  SceneDescription blurred = room_at(0.5f);  // the lamp starts to move while the shutter is open
  blurred.motion_steps = 2;
  for (Instance& inst : blurred.instances) inst.motion = {inst.object_to_world};
  blurred.instances[3].motion = {translate({0.3f, 0, 0})};
  refused(blurred, "motion steps");
  // Still usable after the refusals.
  SceneDescription next = room_at(0.5f);
  ASSERT_TRUE(scene.update(next));
  test::expect_same_image(render(scene), render(RenderScene(room_at(0.5f), grey())));
}

// Under a shutter a moving placement is an Embree instance with a transform per step, and a
// deforming mesh has a vertex buffer per step: both are updated, frame after frame.
TEST(SceneUpdate, MotionBlurredFramesUpdateToTheSameBits) {
  auto blurred_at = [](float t) {
    SceneDescription d = room_at(t);
    d.motion_steps = 3;
    for (Instance& inst : d.instances) inst.motion = {inst.object_to_world, inst.object_to_world};
    d.instances[3].motion = {translate({0.3f * t + 0.05f, 0, 0}), translate({0.3f * t + 0.1f, 0, 0})};  // the lamp
    TriangleMesh& wall = d.meshes[1].primitives[0];  // the back wall leans back over the shutter
    for (int k = 1; k < 3; ++k) {
      MeshArray<glm::vec3> leaned = wall.positions;
      for (glm::vec3& p : leaned) p.z -= 0.1f * k * (p.y + 1.0f) * (1.0f + t);
      wall.motion_positions.push_back(leaned);
    }
    return d;
  };
  RenderScene scene(blurred_at(0.0f), grey());
  SceneDescription next = blurred_at(1.0f);
  ASSERT_TRUE(scene.update(next));
  EXPECT_EQ(scene.rebuilt_triangles, 2 + kTurningQuadTriangles);  // the wall; the turning quad
  test::expect_same_image(render(scene), render(RenderScene(blurred_at(1.0f), grey())));
}

}  // namespace
}  // namespace tessera
