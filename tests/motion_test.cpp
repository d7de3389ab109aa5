// Motion steps read at a time: segments as Embree reads them, transforms in parts
// (renderer/geometry/motion.*), the moving camera, and SceneGeometry's surface at a hit's time lying
// on the surface Embree intersected then.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>

#include "renderer/camera/camera.h"
#include "renderer/geometry/motion.h"
#include "renderer/scene/render_scene.h"
#include "tests/scene_builders.h"

namespace tessera {
namespace {

glm::mat4 rotate_z(float degrees) { return glm::rotate(glm::mat4(1.0f), glm::radians(degrees), vec3(0, 0, 1)); }

void expect_near(const glm::mat4& a, const glm::mat4& b, float tolerance) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(a[c][r], b[c][r], tolerance) << "column " << c << " row " << r;
}

TEST(Motion, SegmentsAreEvenlySpacedAndTheLastOneEndsAtOne) {
  // 3 steps: segment 0 is [0, 1/2), segment 1 is [1/2, 1]; time 1 is the end of the last.
  EXPECT_EQ(motion_segment(0.0f, 3).step, 0);
  EXPECT_FLOAT_EQ(motion_segment(0.25f, 3).fraction, 0.5f);
  EXPECT_EQ(motion_segment(0.5f, 3).step, 1);
  EXPECT_FLOAT_EQ(motion_segment(0.5f, 3).fraction, 0.0f);
  EXPECT_EQ(motion_segment(1.0f, 3).step, 1);
  EXPECT_FLOAT_EQ(motion_segment(1.0f, 3).fraction, 1.0f);
  EXPECT_EQ(motion_segment(0.999f, 2).step, 0);
}

TEST(Motion, DecompositionRebuildsTranslationRotationScaleMirrorAndShear) {
  const glm::mat4 trs = glm::scale(glm::translate(glm::mat4(1.0f), vec3(1, -2, 3)) * rotate_z(30.0f) *
                                       glm::rotate(glm::mat4(1.0f), 0.7f, glm::normalize(vec3(1, 1, 0))),
                                   vec3(2.0f, 0.5f, 3.0f));
  const AffineParts p = decompose(trs);
  expect_near(compose(p), trs, 1e-5f);
  EXPECT_NEAR(p.upper[0][0], 2.0f, 1e-5f);  // glTF's T R S: the scale is the upper part's diagonal
  EXPECT_NEAR(p.upper[1][1], 0.5f, 1e-5f);
  EXPECT_NEAR(p.upper[2][2], 3.0f, 1e-5f);
  EXPECT_NEAR(p.upper[1][0], 0.0f, 1e-5f);
  glm::mat4 mirrored = glm::scale(trs, vec3(1.0f, -1.0f, 1.0f));  // a proper rotation, negative z scale
  expect_near(compose(decompose(mirrored)), mirrored, 1e-5f);
  EXPECT_LT(decompose(mirrored).upper[2][2], 0.0f);
  glm::mat4 sheared = trs;
  sheared[1] += 0.4f * sheared[0];  // y picks up x: a shear
  expect_near(compose(decompose(sheared)), sheared, 1e-5f);
}

// Halfway between 0 and 90 degrees is a 45-degree turn of the same size: averaging the two
// matrices would give cos(45) = 0.71 of it.
TEST(Motion, RotationsTurnAtConstantSpeedWithoutShrinking) {
  const MotionTransform m({rotate_z(0.0f), rotate_z(45.0f), rotate_z(90.0f)});
  for (float t : {0.0f, 0.1f, 0.25f, 0.4f, 0.5f, 0.75f, 0.99f}) expect_near(m.at(t), rotate_z(90.0f * t), 2e-6f);
  const MotionTransform moving({glm::translate(glm::mat4(1.0f), vec3(1, 0, 0)), glm::translate(glm::mat4(1.0f), vec3(3, 2, 0))});
  expect_near(moving.at(0.25f), glm::translate(glm::mat4(1.0f), vec3(1.5f, 0.5f, 0.0f)), 1e-6f);
}

TEST(Motion, CameraMovesOverTheShutterAndAStillOneStaysExactlyAsBefore) {
  Camera cam = test::look_at({0, 0, 5}, {0, 0, 0}, 40.0f);
  const RenderCamera still = make_camera(cam, 32, 32, {});
  cam.motion = {cam.camera_to_world};  // steps equal to step 0: no motion
  const RenderCamera same = make_camera(cam, 32, 32, {});
  EXPECT_FALSE(same.moves());
  const Ray a = still.generate_ray({0.3f, 0.6f}, {0.5f, 0.5f}, 0.7f), b = same.generate_ray({0.3f, 0.6f}, {0.5f, 0.5f}, 0.7f);
  EXPECT_EQ(a.origin, b.origin);
  EXPECT_EQ(a.direction, b.direction);
  EXPECT_EQ(a.time, 0.7f);
  // Moving 2 along +x and turning 90 degrees about +y over the shutter.
  cam.motion = {glm::translate(glm::mat4(1.0f), vec3(2, 0, 0)) * cam.camera_to_world *
                glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), vec3(0, 1, 0))};
  const RenderCamera moving = make_camera(cam, 32, 32, {});
  ASSERT_TRUE(moving.moves());
  const Ray centre = moving.generate_ray({0.5f, 0.5f}, {0.5f, 0.5f}, 0.5f);
  EXPECT_NEAR(glm::distance(centre.origin, vec3(1, 0, 5)), 0.0f, 1e-5f);
  const float s = std::sqrt(0.5f);  // looked down -z, turns to -x: halfway, between them
  EXPECT_NEAR(glm::distance(centre.direction, vec3(-s, 0, -s)), 0.0f, 1e-5f);
}

// A rotating instance (a unit quad turning 90 degrees about z in 3 steps), a deforming mesh
// (a quad whose corners move and whose normals turn), and a small deforming quad placed
// twice (an Embree prototype with a vertex buffer per step), once moving: rays at random
// times hit them where the moved geometry is, and surface() puts the point on the ray.
SceneDescription moving_quads() {
  SceneDescription d;
  d.motion_steps = 3;
  const int m = test::add_material(d, test::diffuse(vec3(0.5f)));
  test::add_mesh(d, test::make_quad({0.5f, 0, 0}, {0.5f, 0, 0}, {0, 0.2f, 0}, m), {glm::translate(glm::mat4(1.0f), vec3(0, 0, -1))});
  d.instances.back().motion = {glm::translate(glm::mat4(1.0f), vec3(0, 0, -1)) * rotate_z(45.0f),
                               glm::translate(glm::mat4(1.0f), vec3(0, 0, -1)) * rotate_z(90.0f)};
  TriangleMesh deforming = test::make_quad({0, 0, -3}, {3, 0, 0}, {0, 3, 0}, m);
  for (int k = 1; k < 3; ++k) {
    MeshArray<vec3> p = deforming.positions, n = deforming.normals;
    for (vec3& v : p) v.z += 0.5f * k * (v.x + 3.0f) / 6.0f;  // tilts about the left edge
    for (vec3& v : n) v = glm::normalize(vec3(-0.5f * k / 6.0f, 0, 1));
    deforming.motion_positions.push_back(p);
    deforming.motion_normals.push_back(n);
  }
  test::add_mesh(d, deforming);
  TriangleMesh rising = test::make_quad({0, 0, 0}, {0.3f, 0, 0}, {0, 0.3f, 0}, m);  // z = 0.4 t
  for (float dz : {0.2f, 0.4f}) {
    rising.motion_positions.push_back(rising.positions);
    for (vec3& v : rising.motion_positions.back()) v.z += dz;
  }
  test::add_mesh(d, rising, {glm::translate(glm::mat4(1.0f), vec3(-0.7f, -0.7f, -2)), glm::translate(glm::mat4(1.0f), vec3(-0.7f, 0.7f, -2))});
  d.instances.back().motion = {glm::translate(glm::mat4(1.0f), vec3(-0.5f, 0.7f, -2)), glm::translate(glm::mat4(1.0f), vec3(-0.3f, 0.7f, -2))};
  return d;
}

TEST(Motion, SurfaceAtTheHitsTimeLiesOnTheRay) {
  RenderScene rs(moving_quads(), {});
  ASSERT_TRUE(rs.moves());
  const SceneGeometry& g = *rs.geometry;
  int instance_hits = 0, deforming_hits = 0, prototype_hits = 0;
  for (int i = 0; i < 2000; ++i) {
    const float u = (i % 40 + 0.5f) / 40.0f, v = (i / 40 + 0.5f) / 50.0f;
    Ray ray{vec3(2.4f * u - 1.2f, 2.4f * v - 1.2f, 1.0f), vec3(0, 0, -1)};
    ray.time = std::fmod(i * 0.618034f, 1.0f);
    HitRecord hit;
    ASSERT_TRUE(g.intersect(ray, hit));
    EXPECT_EQ(hit.time, ray.time);
    const SurfaceHit s = g.surface(ray, hit);
    EXPECT_NEAR(glm::distance(s.p, ray.origin + hit.t * ray.direction), 0.0f, 2e-5f) << "time " << ray.time;
    if (hit.instance != RTC_INVALID_GEOMETRY_ID && s.p.z < -1.5f) {
      ++prototype_hits;  // the rising quads, the second moving 0.4 along x
      EXPECT_NEAR(s.p.z, -2.0f + 0.4f * ray.time, 2e-5f);
      const float cx = s.p.y < 0.0f ? -0.7f : -0.7f + 0.4f * ray.time;
      EXPECT_LE(std::fabs(s.p.x - cx), 0.3f + 1e-5f);
    } else if (hit.instance != RTC_INVALID_GEOMETRY_ID) {
      ++instance_hits;  // the bar at angle 90 t: the point's angle within its half-width
      const float angle = std::atan2(ray.origin.y, ray.origin.x), r = std::hypot(ray.origin.x, ray.origin.y);
      EXPECT_LE(std::fabs(r * std::sin(angle - glm::radians(90.0f) * ray.time)), 0.2f + 1e-4f);
      EXPECT_NEAR(s.ng.z, 1.0f, 1e-5f);
    } else {
      ++deforming_hits;  // z = -3 + 0.5 (2t) (x + 3) / 6, its normals turning alike
      EXPECT_NEAR(s.p.z, -3.0f + ray.time * (s.p.x + 3.0f) / 6.0f, 2e-5f);
      // The normals move linearly between the steps' (-k / 12, 0, 1), as the vertices do.
      const float k = std::min(std::floor(2.0f * ray.time), 1.0f), f = 2.0f * ray.time - k;
      const vec3 n = (1.0f - f) * glm::normalize(vec3(-k / 12.0f, 0, 1)) + f * glm::normalize(vec3(-(k + 1) / 12.0f, 0, 1));
      EXPECT_NEAR(glm::distance(s.ns, glm::normalize(n)), 0.0f, 1e-6f);
    }
  }
  EXPECT_GT(instance_hits, 50);
  EXPECT_GT(deforming_hits, 1000);
  EXPECT_GT(prototype_hits, 100);
}

TEST(Motion, MotionArraysOfAnotherLengthThanTheStepsAreRefused) {
  SceneDescription d = moving_quads();
  d.instances[0].motion.pop_back();
  EXPECT_THROW(RenderScene(d, {}), std::invalid_argument);
  d = moving_quads();
  d.meshes[1].primitives[0].motion_normals[1].pop_back();
  EXPECT_THROW(RenderScene(d, {}), std::invalid_argument);
  d = moving_quads();
  d.motion_steps = 1;  // no motion blur: the arrays are not read at all
  RenderScene still(d, {});
  EXPECT_FALSE(still.moves());
}

}  // namespace
}  // namespace tessera
