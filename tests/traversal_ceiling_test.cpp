// The traversal-only pass `tessera bench` measures tessera against: it traces exactly the
// rays its definition says. Inside a closed sphere of any size every path bounces until its
// limit; with nothing in the scene each camera ray is the whole path; with the camera outside
// a sphere that fills part of the view, every path that enters the sphere's image and bounces
// off its convex outside leaves after one bounce. Camera rays culled (their pixels' rays
// provably miss) are exactly the rays a pass that traces every camera ray spends on those
// pixels.
#include <gtest/gtest.h>

#include "renderer/scene/render_scene.h"
#include "renderer/profile/traversal_ceiling.h"
#include "tests/scene_builders.h"

namespace tessera {
namespace {

RenderCamera camera_at(glm::vec3 eye, glm::vec3 target, float fov, int w, int h) {
  return make_camera(test::look_at(eye, target, fov), w, h, {});
}

// At every scale: its bounces leave the surface as the renderer's do (a fixed minimum
// distance of 1e-4 let the paths of a sphere 2e-4 across skip its short chords and escape).
TEST(TraversalCeiling, AClosedSphereKeepsEveryPathToItsBounceLimitAtAnyScale) {
  for (const float radius : {10.0f, 1e-4f, 1e4f}) {
    SceneDescription scene;
    const int m = test::add_material(scene, test::diffuse(glm::vec3(0.5f)));
    test::add_mesh(scene, test::make_sphere(glm::vec3(0.0f), radius, 3, m, true));
    const RenderScene rs(std::move(scene), EnvironmentParams{});
    const TraversalCeilingParams p{16, 12, 3, 5, 2};
    const RenderCamera cam = camera_at({0, 0, 0.1f * radius}, {0, 0, 0}, 60, 16, 12);
    const TraversalCeilingResult r = trace_traversal_ceiling(rs, cam, p);
    EXPECT_EQ(r.rays, 16u * 12u * 3u * 6u) << "radius " << radius;
    EXPECT_GT(r.seconds, 0.0);
  }
}

TEST(TraversalCeiling, AnEmptySceneTracesOnlyTheCameraRaysOrNoneWhenCulled) {
  const RenderScene rs(SceneDescription{}, EnvironmentParams{});
  TraversalCeilingParams p{8, 8, 4, 8, 1};
  p.cull_camera_rays = false;
  const TraversalCeilingResult r = trace_traversal_ceiling(rs, camera_at({0, 0, 1}, {0, 0, 0}, 60, 8, 8), p);
  EXPECT_EQ(r.rays, 8u * 8u * 4u);
  EXPECT_EQ(r.culled_camera_rays, 0u);
  p.cull_camera_rays = true;
  const TraversalCeilingResult culled = trace_traversal_ceiling(rs, camera_at({0, 0, 1}, {0, 0, 0}, 60, 8, 8), p);
  EXPECT_EQ(culled.rays, 0u);
  EXPECT_EQ(culled.culled_camera_rays, 8u * 8u * 4u);
}

TEST(TraversalCeiling, CulledCameraRaysAreTheRaysTheirPixelsWouldTrace) {
  SceneDescription scene;
  const int m = test::add_material(scene, test::diffuse(glm::vec3(0.5f)));
  test::add_mesh(scene, test::make_sphere(glm::vec3(0.0f), 1.0f, 3, m));
  const RenderScene rs(std::move(scene), EnvironmentParams{});
  const RenderCamera cam = camera_at({0, 0, 6}, {0, 0, 0}, 50, 32, 24);
  TraversalCeilingParams p{32, 24, 4, 8, 2};
  p.cull_camera_rays = false;
  const TraversalCeilingResult all = trace_traversal_ceiling(rs, cam, p);
  p.cull_camera_rays = true;
  const TraversalCeilingResult culled = trace_traversal_ceiling(rs, cam, p);
  EXPECT_GT(culled.culled_camera_rays, 32u * 24u * 4u / 2);  // the sphere takes a fifth of the view
  EXPECT_EQ(all.rays - culled.rays, culled.culled_camera_rays);
}

TEST(TraversalCeiling, AConvexObjectIsLeftAfterOneBounce) {
  SceneDescription scene;
  const int m = test::add_material(scene, test::diffuse(glm::vec3(0.5f)));
  test::add_mesh(scene, test::make_sphere(glm::vec3(0.0f), 1.0f, 4, m));
  const RenderScene rs(std::move(scene), EnvironmentParams{});
  // The whole view inside the sphere's silhouette: every camera ray hits, every bounce leaves.
  const TraversalCeilingResult r = trace_traversal_ceiling(rs, camera_at({0, 0, 5}, {0, 0, 0}, 2, 8, 8), {8, 8, 2, 8, 2});
  EXPECT_EQ(r.rays, 8u * 8u * 2u * 2u);
}

}  // namespace
}  // namespace tessera
