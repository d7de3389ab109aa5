// Alpha modes: MASK cuts out below alphaCutoff (Embree's filters) for every ray; BLEND lets a
// path through with probability 1 - alpha (the integrator's draw) and a shadow ray with
// weight 1 - alpha.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "renderer/render/render.h"
#include "tests/scene_builders.h"

namespace tessera {
namespace {

// A quad of the given alpha (black unless said) in front of an emitter of radiance 1, both
// filling the view, under a black world; the image's pixels.
std::vector<float> see_through_pixels(AlphaMode mode, float alpha, int spp, vec3 colour = vec3(0.0f)) {
  SceneDescription s;
  Material m = test::diffuse(colour);
  m.alpha_mode = mode;
  m.base_color_factor.a = alpha;
  test::add_mesh(s, test::make_quad({0, 0, 0}, {5, 0, 0}, {0, 5, 0}, test::add_material(s, m)));
  test::add_mesh(s, test::make_quad({0, 0, -1}, {9, 0, 0}, {0, 9, 0}, test::add_material(s, test::emitter(vec3(1.0f)))));
  RenderSettings st;
  st.width = st.height = 16;
  st.spp = spp;
  RenderScene rs(std::move(s), EnvironmentParams{});
  const FrameImage img = render_frame(rs, make_camera(test::look_at({0, 0, 3}, {0, 0, 0}, 20.0f), 16, 16, {}), st).image;
  std::vector<float> red;
  for (std::size_t i = 0; i < img.rgb.size(); i += 3) red.push_back(img.rgb[i]);
  return red;
}

double see_through(AlphaMode mode, float alpha, int spp) {
  const std::vector<float> red = see_through_pixels(mode, alpha, spp);
  double sum = 0.0;
  for (float r : red) sum += r;
  return sum / red.size();
}

TEST(RenderAlpha, MaskCutsOutBelowTheCutoffOnly) {
  EXPECT_DOUBLE_EQ(see_through(AlphaMode::Mask, 0.3f, 1), 1.0);  // below 0.5: gone
  EXPECT_DOUBLE_EQ(see_through(AlphaMode::Mask, 0.7f, 1), 0.0);  // above: a black wall
  EXPECT_DOUBLE_EQ(see_through(AlphaMode::Opaque, 0.0f, 1), 0.0);  // OPAQUE ignores alpha
}

TEST(RenderAlpha, BlendTransmitsOneMinusAlphaOnAverage) {
  // 16x16 pixels x 64 samples of a Bernoulli(0.75) event: standard error 0.0017.
  EXPECT_NEAR(see_through(AlphaMode::Blend, 0.25f, 64), 0.75, 0.01);
}

// Which of a pixel's paths pass is a draw of its sampler: a padded Sobol dimension, whose 2^k
// points over a pixel put one in each interval of width 2^-k. A white quad is met with
// probability alpha (its share, path_tracer.cpp: alpha x albedo 1), where it shows nothing
// (the emitter lights its back; the world is black), and passed with weight 1: exactly 48 of
// 64 samples pass at alpha 0.25. At alpha 0.2 and 16 samples, three intervals of 1/16 lie
// below 0.2, twelve above, and the one across it passes when its point is above 0.2: 12 or 13
// of 16 at each pixel, where independent choices (binomial, sd 1.6) would stray far wider.
TEST(RenderAlpha, BlendPassesAStratifiedShareOfEachPixelsSamples) {
  for (float r : see_through_pixels(AlphaMode::Blend, 0.25f, 64, vec3(1.0f))) EXPECT_FLOAT_EQ(r, 0.75f);
  for (float r : see_through_pixels(AlphaMode::Blend, 0.2f, 16, vec3(1.0f))) EXPECT_TRUE(r == 0.75f || r == 0.8125f) << r;
}

// A dark surface is met less often than its alpha, and the paths divided by the probability of
// their choice: a black quad of alpha 0.25 (its share 0.25 x 0.1, the floor) is passed with
// probability 0.75 / 0.775, weight 0.775, so 61 or 62 of 64 samples pass (0.9677 lies in the
// 62nd interval): each pixel 0.7387 or 0.7508, around the expected 0.75.
TEST(RenderAlpha, ADarkBlendSurfaceIsPassedMoreOftenWithLessWeight) {
  for (float r : see_through_pixels(AlphaMode::Blend, 0.25f, 64))
    EXPECT_TRUE(std::fabs(r - 61 * 0.775f / 64) < 1e-5f || std::fabs(r - 62 * 0.775f / 64) < 1e-5f) << r;
}

// A floor under a directional light, shaded by a MASK quad: cut out, it casts no shadow.
TEST(RenderAlpha, ShadowRaysSeeTheCutOut) {
  for (float alpha : {0.2f, 0.9f}) {
    SceneDescription s;
    test::add_mesh(s, test::make_quad({0, 0, 0}, {20, 0, 0}, {0, 0, -20}, test::add_material(s, test::diffuse(vec3(0.5f)))));
    Material leaf = test::diffuse(vec3(0.5f));
    leaf.alpha_mode = AlphaMode::Mask;
    leaf.base_color_factor.a = alpha;
    leaf.double_sided = true;
    test::add_mesh(s, test::make_quad({0, 1, 0}, {3, 0, 0}, {0, 0, -3}, test::add_material(s, leaf)));
    PunctualLight sun;
    sun.type = PunctualLight::Type::Directional;
    sun.direction = {0, -1, 0};
    sun.intensity = 2.0f;
    s.lights.push_back(sun);
    RenderSettings st;
    st.width = st.height = 4;
    st.spp = 2;
    st.max_bounces = 1;
    RenderScene rs(std::move(s), EnvironmentParams{});
    // Looking up at the floor's underside is impossible; look at the floor under the leaf
    // from the side, below the leaf's height.
    const FrameImage img =
        render_frame(rs, make_camera(test::look_at({0, 0.5f, 2}, {0, 0, 0}, 1.0f), 4, 4, {}), st).image;
    const double expected = alpha < 0.5f ? 0.5 / M_PI * 2.0 : 0.0;
    for (std::size_t i = 0; i < img.rgb.size(); i += 3) EXPECT_NEAR(img.rgb[i], expected, 1e-4) << "alpha " << alpha;
  }
}

}  // namespace
}  // namespace tessera
