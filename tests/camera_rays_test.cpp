// RenderCamera::generate_rays, which makes a group of camera rays at once (a still pinhole's
// four at a time in SSE), against generate_ray one by one: every ray the same bit for bit,
// for every group size and kind of camera, so images do not depend on how rays are grouped.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "renderer/camera/camera.h"
#include "tests/scene_builders.h"

namespace tessera {
namespace {

bool same_bits(const Ray& a, const Ray& b) {
  const float fa[] = {a.origin.x, a.origin.y, a.origin.z, a.direction.x, a.direction.y, a.direction.z, a.tmin, a.tmax, a.time};
  const float fb[] = {b.origin.x, b.origin.y, b.origin.z, b.direction.x, b.direction.y, b.direction.z, b.tmin, b.tmax, b.time};
  return std::memcmp(fa, fb, sizeof fa) == 0;
}

void expect_same_rays(const RenderCamera& rc, const char* what) {
  std::mt19937 gen(11);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  for (int n = 1; n <= 19; ++n) {  // whole groups of four and every remainder
    std::vector<vec2> film(n), lens(n);
    std::vector<float> time(n);
    for (int k = 0; k < n; ++k) {
      film[k] = {u01(gen), u01(gen)};
      lens[k] = {u01(gen), u01(gen)};
      time[k] = u01(gen);
    }
    film[0] = {0.0f, 1.0f};  // the frame's corner
    std::vector<Ray> rays(n);
    rc.generate_rays(film.data(), lens.data(), time.data(), n, rays.data());
    for (int k = 0; k < n; ++k)
      EXPECT_TRUE(same_bits(rays[k], rc.generate_ray(film[k], lens[k], time[k]))) << what << ": n " << n << ", ray " << k;
  }
}

TEST(CameraRays, GroupsAreTheSingleRaysBitForBit) {
  Camera cam = test::look_at({1.5f, 2.0f, 3.2f}, {0.1f, -0.2f, 0.0f}, 37.0f);
  expect_same_rays(make_camera(cam, 640, 360, {}), "pinhole");
  Camera clipped = cam;
  clipped.znear = 0.25f;
  clipped.zfar = 40.0f;
  expect_same_rays(make_camera(clipped, 640, 360, {}), "pinhole with near and far planes");
  clipped.zfar = 0.0f;
  expect_same_rays(make_camera(clipped, 640, 360, {}), "pinhole with a near plane");
  expect_same_rays(make_camera(cam, 64, 48, {0.0f, 0.5f, 7.0f}), "thin lens");
  Camera ortho = cam;
  ortho.projection = Camera::Projection::Orthographic;
  ortho.ymag = 2.0f;
  expect_same_rays(make_camera(ortho, 640, 360, {}), "orthographic");
  Camera moving = cam;
  moving.motion = {glm::translate(cam.camera_to_world, vec3(0.3f, 0.0f, 0.1f))};
  expect_same_rays(make_camera(moving, 640, 360, {}), "moving pinhole");
}

}  // namespace
}  // namespace tessera
