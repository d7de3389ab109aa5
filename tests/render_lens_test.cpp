// The thin lens: a point on the focal plane stays sharp; a point off it spreads into a
// disk whose radius is the predicted circle of confusion.
#include <gtest/gtest.h>

#include <cmath>

#include "renderer/render/render.h"
#include "tests/scene_builders.h"

namespace tessera {
namespace {

// Lens rays for one film point all pass through the same point of the focal plane.
TEST(ThinLens, RaysForOneFilmPointMeetOnTheFocalPlane) {
  Camera cam = test::look_at({1, 2, 3}, {0, 0, 0}, 40.0f);
  RenderCamera rc = make_camera(cam, 64, 48, {0.0f, 0.5f, 7.0f});
  const vec2 film(0.3f, 0.8f);
  const vec3 forward = rc.forward();
  vec3 meet(0.0f);
  for (int i = 0; i < 16; ++i) {
    const Ray ray = rc.generate_ray(film, {(i % 4 + 0.5f) / 4.0f, (i / 4 + 0.5f) / 4.0f});
    const float t = glm::dot(rc.position() + forward * 7.0f - ray.origin, forward) / glm::dot(ray.direction, forward);
    const vec3 p = ray.origin + t * ray.direction;
    if (i == 0) meet = p;
    EXPECT_NEAR(glm::distance(p, meet), 0.0f, 1e-5f) << "lens sample " << i;
    EXPECT_LE(glm::length(ray.origin - rc.position()), 0.25f + 1e-6f);  // on the lens disk
  }
}

// Image of a small emissive square (side `side` at depth `depth`) through the lens,
// returned as the radius of the blur disk measured from the image's second moment.
// A uniform disk of radius r has E[|x - c|^2] = r^2 / 2; the square (side s' in pixels)
// and the pixel's box filter each add their own variance s'^2 / 6 and 1 / 6.
struct BlurMeasurement {
  double radius_pixels;
  double square_pixels;
};

BlurMeasurement measure_blur(float depth, float side, float focus, float aperture) {
  SceneDescription scene;
  const int m = test::add_material(scene, test::emitter(vec3(1.0f)));
  test::add_mesh(scene, test::make_quad({0, 0, -depth}, {side / 2, 0, 0}, {0, side / 2, 0}, m));
  RenderSettings s;
  s.width = s.height = 96;
  s.spp = 1024;
  s.max_bounces = 0;
  const float fov = 30.0f;
  RenderScene rs(std::move(scene), EnvironmentParams{});
  const RenderCamera rc = rs.camera(test::look_at({0, 0, 0}, {0, 0, -1}, fov), s.width, s.height, {0.0f, aperture, focus});
  const FrameImage img = render_frame(rs, rc, s).image;
  double sum = 0, cx = 0, cy = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const double v = img.rgb[3 * (y * img.width + x)];
      sum += v;
      cx += v * (x + 0.5);
      cy += v * (y + 0.5);
    }
  cx /= sum;
  cy /= sum;
  double m2 = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      m2 += img.rgb[3 * (y * img.width + x)] * (std::pow(x + 0.5 - cx, 2) + std::pow(y + 0.5 - cy, 2));
  m2 /= sum;
  const double pixels_per_unit_at_focus = s.height / (2.0 * focus * std::tan(glm::radians(fov / 2)));
  const double square = side * (focus / depth) * pixels_per_unit_at_focus;  // pinhole projection
  const double disk_m2 = m2 - (square * square + 1.0) / 6.0;
  return {std::sqrt(std::max(0.0, 2.0 * disk_m2)), square};
}

TEST(ThinLens, PointOnTheFocalPlaneStaysSharp) {
  const BlurMeasurement b = measure_blur(5.0f, 0.04f, 5.0f, 0.8f);
  EXPECT_LT(b.radius_pixels, 0.5);  // within the pixel: no blur
}

TEST(ThinLens, PointOffTheFocalPlaneBlursByTheCircleOfConfusion) {
  const float focus = 5.0f, aperture = 0.8f, fov = 30.0f;
  for (float depth : {10.0f, 3.5f}) {
    const BlurMeasurement b = measure_blur(depth, 0.08f * depth / 10.0f, focus, aperture);
    // Similar triangles: lens radius R, point at depth z, focal plane at F: the cone of
    // rays through the point covers a disk of radius R |z - F| / z on the focal plane.
    const double coc_world = (aperture / 2) * std::abs(depth - focus) / depth;
    const double expected = coc_world * 96 / (2.0 * focus * std::tan(glm::radians(fov / 2)));
    EXPECT_NEAR(b.radius_pixels, expected, 0.05 * expected) << "depth " << depth;
  }
}

}  // namespace
}  // namespace tessera
