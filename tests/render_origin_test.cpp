// The render frame (renderer/geometry/render_origin.h): a scene far from the origin for its size is
// rendered about its centre (an animation's frame about a corner of a grid), with every
// placement, camera and light moved alike and the camera's projections still of world
// coordinates; anything else stays where it is.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "renderer/render/render.h"
#include "renderer/geometry/render_origin.h"
#include "renderer/scene/render_scene.h"
#include "tests/scene_builders.h"

namespace tessera {
namespace {

// A unit quad at `at`, a camera 3 in front of it, a point light above it, all moving.
SceneDescription quad_at(const vec3& at) {
  SceneDescription scene;
  const glm::mat4 place = glm::translate(glm::mat4(1.0f), at);
  test::add_mesh(scene, test::make_quad({0, 0, 0}, {0.5f, 0, 0}, {0, 0.5f, 0}, test::add_material(scene, test::diffuse(vec3(0.5f)))),
                 {place});
  scene.instances[0].motion = {place};
  Camera camera = test::look_at(at + vec3(0, 0, 3), at, 40.0f);
  camera.motion = {camera.camera_to_world};
  scene.cameras.push_back(camera);
  PunctualLight light;
  light.position = at + vec3(0, 2, 0);
  light.light_to_world = glm::translate(glm::mat4(1.0f), light.position);
  light.motion = {light.light_to_world};
  scene.lights.push_back(light);
  return scene;
}

TEST(RenderOrigin, OnlyASceneFarForItsSizeMoves) {
  EXPECT_EQ(render_origin(quad_at({0, 0, 0})), vec3(0.0f));
  EXPECT_EQ(render_origin(quad_at({50, 0, 0})), vec3(0.0f));  // 50 sizes out: floats hold it finely
  EXPECT_EQ(render_origin(quad_at({1e4f, -2e4f, 5e3f})), vec3(1e4f, -2e4f, 5e3f));  // its centre
  // An animation's frame: the corner nearest its centre of a grid of 8-unit cells (the quad is
  // 1 across), so that nearby frames share it.
  SceneDescription animated = quad_at({1e4f + 3.0f, -2e4f - 5.0f, 0});
  animated.animated = true;
  EXPECT_EQ(render_origin(animated), vec3(1e4f, -2e4f - 8.0f, 0.0f));
  animated.animated = false;
  EXPECT_EQ(render_origin(animated), vec3(1e4f + 3.0f, -2e4f - 5.0f, 0.0f));
  EXPECT_EQ(render_origin(SceneDescription{}), vec3(0.0f));
  SceneDescription tiny;  // a tenth of a millimetre across, half a metre out: 5,000 sizes
  tiny.bounds = {vec3(0.5f), vec3(0.5001f)};
  EXPECT_EQ(render_origin(tiny), tiny.bounds.center());
}

TEST(RenderOrigin, PlacementsCamerasLightsAndBoundsMoveAlike) {
  const vec3 at(1e4f, -2e4f, 5e3f);
  SceneDescription scene = quad_at(at);
  move_to_render_frame(scene, at);
  EXPECT_EQ(scene.instances[0].object_to_world[3], glm::vec4(0, 0, 0, 1));
  EXPECT_EQ(scene.instances[0].motion[0][3], glm::vec4(0, 0, 0, 1));
  EXPECT_NEAR(glm::length(glm::vec3(scene.cameras[0].camera_to_world[3]) - vec3(0, 0, 3)), 0.0f, 2e-3f);
  EXPECT_EQ(scene.cameras[0].motion[0], scene.cameras[0].camera_to_world);
  EXPECT_EQ(scene.lights[0].position, vec3(0, 2, 0));
  EXPECT_EQ(scene.lights[0].light_to_world[3], glm::vec4(0, 2, 0, 1));
  EXPECT_EQ(scene.lights[0].motion[0][3], glm::vec4(0, 2, 0, 1));
  EXPECT_EQ(scene.bounds.lo, vec3(-0.5f, -0.5f, 0.0f));
  EXPECT_EQ(scene.bounds.hi, vec3(0.5f, 0.5f, 0.0f));
}

// The render camera of a far scene: its rays start near the render frame's origin, and its
// projection is the world camera's.
TEST(RenderOrigin, TheCameraLooksFromTheRenderFrameButProjectsTheWorld) {
  const vec3 at(1e4f, -2e4f, 5e3f);
  SceneDescription scene = quad_at(at);
  const Camera world = scene.cameras[0];
  const RenderScene rs(std::move(scene), EnvironmentParams{});
  ASSERT_EQ(rs.origin, at);
  const RenderCamera rc = rs.camera(world, 8, 8, {});
  EXPECT_NEAR(glm::length(rc.position() - vec3(0, 0, 3)), 0.0f, 2e-3f);
  const glm::mat4 expected = glm::inverse(world.camera_to_world), got = rc.world_to_camera();
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(got[c][r], expected[c][r], c == 3 ? 4e-3f : 1e-6f) << c << "," << r;
  EXPECT_NEAR(glm::length(vec3(got * glm::vec4(at, 1.0f)) - vec3(0, 0, -3)), 0.0f, 4e-3f);
  // A world camera handed to the moved scene would look at empty space: it is refused.
  RenderSettings s;
  s.width = s.height = 8;
  s.spp = 1;
  EXPECT_THROW(render_frame(rs, make_camera(world, 8, 8, {}), s), std::invalid_argument);
  EXPECT_NO_THROW(render_frame(rs, rc, s));
  // A scene near the origin is not moved: the same camera as make_camera's, bit for bit.
  SceneDescription near = quad_at({1, 2, 3});
  const Camera near_camera = near.cameras[0];
  const RenderScene near_scene(std::move(near), EnvironmentParams{});
  EXPECT_EQ(near_scene.origin, vec3(0.0f));
  EXPECT_EQ(near_scene.camera(near_camera, 8, 8, {}).camera_to_world, make_camera(near_camera, 8, 8, {}).camera_to_world);
}

}  // namespace
}  // namespace tessera
