// camera_ray_escaped, the shortcut CameraSampler takes for a camera ray that hits nothing,
// against the whole path tracer given the same miss: the same radiance bit for bit, the same
// counters, for a uniform background and an environment image, with and without the clamp
// and the transparent film, and for a background no finite value can come from.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "renderer/integrator/path_tracer.h"
#include "tests/scene_builders.h"
#include "imageio/environment_image.h"

namespace tessera {
namespace {

RenderScene scene_with(const EnvironmentParams& env) {
  SceneDescription d;
  test::add_mesh(d, test::make_quad({0, 0, -5}, {1, 0, 0}, {0, 1, 0}, test::add_material(d, test::diffuse(vec3(0.5f)))));
  return RenderScene(std::move(d), env);
}

void expect_same_as_path(const RenderScene& rs, const PathTracerParams& params) {
  std::mt19937 gen(7);
  std::normal_distribution<float> n01;
  for (int i = 0; i < 200; ++i) {
    const vec3 d = glm::normalize(vec3(n01(gen), n01(gen), n01(gen)));
    const Ray ray{vec3(0.0f), d, 0.0f, std::numeric_limits<float>::infinity(), 0.0f};
    const ClosestHit miss;  // found = false
    Sampler rng(SamplerKind::sobol, 3, 4, static_cast<std::uint32_t>(i), 1);
    FirstHit first;
    PathCounters full, fast;
    const vec3 a = trace_path_from(rs, params, ray, &miss, rng, first, full);
    const vec3 b = camera_ray_escaped(rs, params, ray, fast);
    for (int c = 0; c < 3; ++c) EXPECT_TRUE(same_bits(a[c], b[c])) << "ray " << i << " channel " << c << ": " << a[c] << " " << b[c];
    EXPECT_EQ(full.rays, fast.rays);
    EXPECT_EQ(full.dropped, fast.dropped);
    EXPECT_FALSE(first.hit);
  }
}

TEST(CameraEscape, UniformBackgroundAsThePathTracerSeesIt) {
  EnvironmentParams env;
  env.background = vec3(0.8f, 1.7f, 0.25f);
  const RenderScene rs = scene_with(env);
  expect_same_as_path(rs, {});
  PathTracerParams clamped;
  clamped.clamp = 1.0f;  // below the background's luminance: scaled down
  expect_same_as_path(rs, clamped);
  PathTracerParams transparent;
  transparent.transparent_background = true;  // no background in RGB
  expect_same_as_path(rs, transparent);
}

TEST(CameraEscape, EnvironmentImageAsThePathTracerSeesIt) {
  EnvironmentParams env;
  env.image_path = std::string(TESSERA_SOURCE_DIR) + "/scenes/env/spruit_sunrise_1k.hdr";
  env.image = read_environment_image(env.image_path);
  env.scale = 3.0f;
  env.rotate_degrees = 40.0f;
  expect_same_as_path(scene_with(env), {});
}

TEST(CameraEscape, NonFiniteBackgroundIsDroppedAlike) {
  EnvironmentParams env;
  env.background = vec3(std::numeric_limits<float>::infinity());
  expect_same_as_path(scene_with(env), {});
  PathCounters counters;
  const Ray ray{vec3(0.0f), vec3(0, 1, 0), 0.0f, std::numeric_limits<float>::infinity(), 0.0f};
  const vec3 r = camera_ray_escaped(scene_with(env), {}, ray, counters);
  EXPECT_EQ(r, vec3(0.0f));
  EXPECT_EQ(counters.dropped, 1u);
}

}  // namespace
}  // namespace tessera
