// The environment map's direction mapping, against Blender's equirectangular formula after
// Blender's glTF axis conversion (x_b = x, y_b = -z, z_b = y): the same image must light a
// scene the same way in both renderers.
#include <gtest/gtest.h>

#include <cmath>

#include "renderer/environment.h"
#include "renderer/sampler.h"

namespace tessera {
namespace {

vec2 blender_uv(const vec3& d) {  // Cycles' direction_to_equirectangular, v from the top row
  const double xb = d.x, yb = -d.z, zb = d.y;
  const double u = 0.5 - std::atan2(yb, xb) / (2 * M_PI);
  const double v_up = 0.5 + std::atan2(zb, std::hypot(xb, yb)) / M_PI;
  return vec2(static_cast<float>(u), static_cast<float>(1.0 - v_up));
}

TEST(Environment, MappingMatchesBlender) {
  const Environment env(EnvironmentParams{});
  for (int i = 0; i < 1000; ++i) {
    SampleStream rng(i, 0, 0, 3);
    const float z = 2 * rng.next() - 1, phi = 2 * kPi * rng.next(), r = std::sqrt(1 - z * z);
    const vec3 d(r * std::cos(phi), z, r * std::sin(phi));
    const vec2 ours = env.direction_to_uv(d), theirs = blender_uv(d);
    const float du = std::fabs(ours.x - theirs.x);
    EXPECT_LT(std::fmin(du, 1.0f - du), 1e-5f) << d.x << " " << d.y << " " << d.z;  // u wraps around
    EXPECT_NEAR(ours.y, theirs.y, 1e-5f);
  }
  EXPECT_NEAR(env.direction_to_uv({1, 0, 0}).x, 0.5f, 1e-6f);  // the image centre faces +X
  EXPECT_NEAR(env.direction_to_uv({0, 1, 0}).y, 0.0f, 1e-6f);  // the top row is straight up
}

TEST(Environment, RotationTurnsTheMapAboutY) {
  EnvironmentParams p;
  p.rotate_degrees = 90.0f;
  const Environment rotated(p), plain(EnvironmentParams{});
  // Turning the map by +90 degrees about +Y moves what was at +X to -Z (right-handed).
  const vec2 a = plain.direction_to_uv({1, 0, 0}), b = rotated.direction_to_uv({0, 0, -1});
  EXPECT_NEAR(a.x, b.x, 1e-5f);
  EXPECT_NEAR(a.y, b.y, 1e-5f);
}

}  // namespace
}  // namespace tessera
