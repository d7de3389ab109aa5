// The denoiser's features as the path tracer records them: through a mirror, the albedo and
// normal of what the mirror shows (renderer/integrator/path_tracer.cpp).
#include <gtest/gtest.h>

#include <cmath>

#include "renderer/render/render.h"
#include "tests/scene_builders.h"

namespace tessera {
namespace {

using test::add_material;
using test::add_mesh;

// A metal quad at (0, 0, -2) turned 45 degrees about y (normal (1, 0, 1) / sqrt 2, towards the
// camera at the origin), so the camera's rays (along -z) leave it along +x; there, unless
// `wall` is off, a diffuse quad at x = 2 facing -x with base colour kWall. Every pixel of the
// narrow (6 degree) view sees the metal. Background: a constant environment.
const vec3 kMetal(0.9f, 0.5f, 0.2f), kWall(0.2f, 0.6f, 0.3f), kSky(0.5f, 1.0f, 2.0f);

FrameImage render_metal(float roughness, bool wall) {
  SceneDescription scene;
  Material metal;
  metal.base_color_factor = glm::vec4(kMetal, 1.0f);
  metal.metallic_factor = 1.0f;
  metal.roughness_factor = roughness;
  const float h = 0.5f / std::sqrt(2.0f);
  add_mesh(scene, test::make_quad({0, 0, -2}, {h, 0, -h}, {0, 0.5f, 0}, add_material(scene, metal)));
  if (wall) add_mesh(scene, test::make_quad({2, 0, -2}, {0, 0, 2}, {0, 2, 0}, add_material(scene, test::diffuse(kWall))));
  RenderSettings s;
  s.width = s.height = 8;
  s.spp = 4;
  s.aovs.albedo = s.aovs.normal = true;
  EnvironmentParams env;
  env.background = kSky;
  RenderScene rs(std::move(scene), env);
  return render_frame(rs, make_camera(test::look_at({0, 0, 0}, {0, 0, -1}, 6.0f), s.width, s.height, {}), s).image;
}

// A metal's reflectance at 45 degrees (Schlick): F0 + (1 - F0)(1 - cos 45)^5, 0.2% above F0.
float schlick45(float f0) { return f0 + (1.0f - f0) * std::pow(1.0f - std::sqrt(0.5f), 5.0f); }

TEST(DenoiseFeatures, AMirrorShowsTheAlbedoAndNormalOfWhatItReflects) {
  const FrameImage img = render_metal(0.0f, true);
  for (std::size_t i = 0; i < img.albedo.size() / 3; ++i)
    for (int k = 0; k < 3; ++k) {
      // The wall's base colour through the mirror's reflectance (its sampled weight: GGX at
      // the smallest alpha, a near-delta lobe, is F times a shadowing term of 1 within 1%).
      EXPECT_NEAR(img.albedo[3 * i + k], schlick45(kMetal[k]) * kWall[k], 0.01f * kWall[k]) << i << " " << k;
      EXPECT_NEAR(img.normal[3 * i + k], vec3(-1, 0, 0)[k], 1e-4f) << i << " " << k;  // the wall's
    }
}

TEST(DenoiseFeatures, AMirrorShowsTheEnvironmentItReflectsAsAlbedo) {
  const FrameImage img = render_metal(0.0f, false);
  const float n = 1.0f / std::sqrt(2.0f);
  for (std::size_t i = 0; i < img.albedo.size() / 3; ++i)
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(img.albedo[3 * i + k], schlick45(kMetal[k]) * kSky[k], 0.01f * kSky[k]) << i << " " << k;
      // Nothing further to show: the normal stays the mirror's own.
      EXPECT_NEAR(img.normal[3 * i + k], vec3(n, 0, n)[k], 1e-4f) << i << " " << k;
    }
}

TEST(DenoiseFeatures, AGlossyMetalKeepsItsOwnBaseColourAndNormal) {
  // Roughness 0.1 (alpha 0.01) is above the mirror threshold (alpha 0.0025): the features are
  // the surface's own, exactly, whatever its reflection.
  const FrameImage img = render_metal(0.1f, true);
  const float n = 1.0f / std::sqrt(2.0f);
  for (std::size_t i = 0; i < img.albedo.size() / 3; ++i)
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(img.albedo[3 * i + k], kMetal[k], 1e-6f) << i << " " << k;
      EXPECT_NEAR(img.normal[3 * i + k], vec3(n, 0, n)[k], 1e-4f) << i << " " << k;
    }
}

}  // namespace
}  // namespace tessera
