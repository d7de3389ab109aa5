// The light tree (renderer/lights/light_tree.h): every light's probability is the product of
// the branch probabilities on its way down, all of them sum to 1, sampling chooses each light
// exactly as often as that probability says, only lights that cannot reach a point are never
// chosen, and a floor under a grid of point lights renders the closed-form sum of their
// inverse-square irradiances whether the tree samples one light or every light is sampled.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "renderer/lights/light_tree.h"
#include "renderer/lights/punctual_lights.h"
#include "renderer/render/render.h"
#include "tests/pixel_stats.h"
#include "tests/scene_builders.h"

namespace tessera {
namespace {

std::vector<PunctualLight> random_lights(int count, unsigned seed, bool spots = true) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> pos(-5.0f, 5.0f), unit(0.0f, 1.0f);
  std::vector<PunctualLight> lights;
  for (int i = 0; i < count; ++i) {
    PunctualLight l;
    l.type = spots && i % 3 == 2 ? PunctualLight::Type::Spot : PunctualLight::Type::Point;
    l.position = {pos(rng), pos(rng), pos(rng)};
    l.direction = glm::normalize(vec3(pos(rng), pos(rng), pos(rng)) + vec3(0.0f, 0.0f, 1e-3f));
    l.intensity = 0.1f + 10.0f * unit(rng);
    l.color = vec3(0.2f + unit(rng), 0.2f + unit(rng), 0.2f + unit(rng));
    l.outer_cone_angle = 0.2f + 1.2f * unit(rng);
    lights.push_back(l);
  }
  PunctualLight sun;
  sun.type = PunctualLight::Type::Directional;
  lights.push_back(sun);  // never in the tree
  return lights;
}

// Point lights reach every point: their probabilities sum to 1.
TEST(LightTree, EveryLightsProbabilityIsTheProductOfItsBranchesAndTheySumToOne) {
  for (int count : {1, 2, 3, 7, 33}) {
    const std::vector<PunctualLight> lights = random_lights(count, 11u + count, false);
    const LightTree tree(lights);
    ASSERT_EQ(tree.size(), std::size_t(count));
    ASSERT_EQ(tree.directional(), std::vector<std::uint32_t>{std::uint32_t(count)});
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> pos(-6.0f, 6.0f);
    for (int trial = 0; trial < 50; ++trial) {
      const vec3 p(pos(rng), pos(rng), pos(rng));
      const vec3 n = trial % 2 ? glm::normalize(vec3(pos(rng), pos(rng), pos(rng))) : vec3(0.0f);
      double sum = 0.0;
      for (std::uint32_t i = 0; i < lights.size(); ++i) sum += tree.pmf(p, n, i);
      EXPECT_EQ(tree.pmf(p, n, std::uint32_t(count)), 0.0f);  // the directional light
      EXPECT_NEAR(sum, 1.0, 1e-5) << count << " lights";
      // The walk's probability is the same product, factor by factor.
      for (float u : {0.0f, 0.3f, 0.77f, 0.999f}) {
        const LightTree::Choice c = tree.sample(p, n, u);
        ASSERT_GT(c.pmf, 0.0f);
        EXPECT_EQ(c.pmf, tree.pmf(p, n, c.light));
      }
    }
  }
}

// Spots facing away from a point have no probability there; a subtree of them is a dead end
// (no light chosen, the sample adds nothing). Unbiased as long as every light that does reach
// the point keeps a probability: the bounds must hold each light's cone.
TEST(LightTree, EverySpotThatReachesAPointHasAProbabilityThere) {
  for (int count : {3, 7, 33, 100}) {
    const std::vector<PunctualLight> lights = random_lights(count, 3u + count);
    const LightTree tree(lights);
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> pos(-6.0f, 6.0f);
    int reached = 0;
    for (int trial = 0; trial < 200; ++trial) {
      const vec3 p(pos(rng), pos(rng), pos(rng));
      const vec3 n = glm::normalize(vec3(pos(rng), pos(rng), pos(rng)));
      double sum = 0.0;
      for (std::uint32_t i = 0; i + 1 < lights.size(); ++i) {
        const float pmf = tree.pmf(p, n, i);
        sum += pmf;
        LightSample ls;
        if (sample_punctual_light(lights[i], {lights[i].position, lights[i].direction}, p, ls) &&
            std::fabs(glm::dot(ls.wi, n)) > 1e-4f) {
          EXPECT_GT(pmf, 0.0f) << "light " << i << " of " << count << " reaches the point";
          ++reached;
        }
        const LightTree::Choice c = tree.sample(p, n, float(i) / lights.size());
        if (c.pmf > 0.0f) {
          EXPECT_EQ(c.pmf, tree.pmf(p, n, c.light));
        }
      }
      EXPECT_LE(sum, 1.0 + 1e-5);
    }
    EXPECT_GT(reached, 0);
  }
}

// sample() inverts u: the share of evenly spaced u that choose a light is its probability.
TEST(LightTree, SamplingChoosesEachLightAsOftenAsItsProbability) {
  const std::vector<PunctualLight> lights = random_lights(12, 5u);
  const LightTree tree(lights);
  const vec3 p(0.5f, -0.25f, 1.0f), n = glm::normalize(vec3(0.2f, 1.0f, -0.1f));
  const int samples = 1 << 18;
  std::vector<int> chosen(lights.size(), 0);
  for (int k = 0; k < samples; ++k) {
    const LightTree::Choice c = tree.sample(p, n, (k + 0.5f) / samples);
    ASSERT_GT(c.pmf, 0.0f);
    ++chosen[c.light];
  }
  for (std::uint32_t i = 0; i < lights.size(); ++i)
    EXPECT_NEAR(double(chosen[i]) / samples, tree.pmf(p, n, i), 2e-5) << "light " << i;
}

TEST(LightTree, OnlyASpotThatCannotReachThePointIsNeverChosen) {
  std::vector<PunctualLight> lights(2);
  lights[0].type = PunctualLight::Type::Spot;
  lights[0].position = {0.0f, 2.0f, 0.0f};
  lights[0].direction = {0.0f, -1.0f, 0.0f};  // down, a 30 degree cone
  lights[0].outer_cone_angle = 0.5235988f;
  lights[1].position = {5.0f, 2.0f, 0.0f};  // a point light
  const LightTree tree(lights);
  const vec3 up(0.0f, 1.0f, 0.0f);
  EXPECT_GT(tree.pmf({0.5f, 0.0f, 0.0f}, up, 0), 0.0f);  // inside the cone
  EXPECT_EQ(tree.pmf({3.0f, 0.0f, 0.0f}, up, 0), 0.0f);  // 56 degrees off its axis
  EXPECT_EQ(tree.pmf({3.0f, 0.0f, 0.0f}, up, 1), 1.0f);
  EXPECT_EQ(tree.pmf({0.0f, 3.0f, 0.0f}, up, 0), 0.0f);  // behind it
}

TEST(LightTree, AutoUsesTheTreeWithMoreThanEightPointAndSpotLights) {
  EXPECT_FALSE(LightTree(random_lights(8, 1u)).used(LightTreeUse::Auto));
  EXPECT_TRUE(LightTree(random_lights(9, 1u)).used(LightTreeUse::Auto));
  EXPECT_TRUE(LightTree(random_lights(1, 1u)).used(LightTreeUse::On));
  EXPECT_FALSE(LightTree(random_lights(40, 1u)).used(LightTreeUse::Off));
  EXPECT_FALSE(LightTree(std::vector<PunctualLight>{}).used(LightTreeUse::On));
}

// A white Lambertian floor (albedo a) under a 16 x 16 grid of point lights of different
// intensities: the radiance at x is a/pi * sum_i I_i cos(theta_i) / d_i^2.
TEST(LightTree, AFloorUnderAGridOfPointLightsMatchesTheInverseSquareSum) {
  constexpr float kAlbedo = 0.8f;
  SceneDescription d;
  test::add_mesh(d, test::make_quad({-50, 0, 50}, {100, 0, 0}, {0, 0, -100}, test::add_material(d, test::diffuse(vec3(kAlbedo)))));
  for (int row = 0; row < 16; ++row)
    for (int col = 0; col < 16; ++col) {
      PunctualLight l;
      l.position = {(col - 7.5f) * 0.4f, 0.6f + 0.05f * (row % 3), (row - 7.5f) * 0.4f};
      l.intensity = 0.02f * (1 + (row * 16 + col) % 5);
      d.lights.push_back(l);
    }
  const std::vector<PunctualLight> lights = d.lights;
  RenderScene scene(std::move(d), EnvironmentParams{});
  for (vec3 target : {vec3(0.0f), vec3(1.3f, 0.0f, -0.7f), vec3(4.0f, 0.0f, 3.5f)}) {
    double expected = 0.0;
    for (const PunctualLight& l : lights) {
      const vec3 to = l.position - target;
      const double d2 = glm::dot(to, to);
      expected += l.intensity * (to.y / std::sqrt(d2)) / d2;
    }
    expected *= kAlbedo / M_PI;
    for (LightTreeUse use : {LightTreeUse::On, LightTreeUse::Off}) {
      RenderSettings st;
      st.width = st.height = 4;
      st.spp = use == LightTreeUse::On ? 1024 : 4;
      st.max_bounces = 1;
      st.light_tree = use;
      const Camera cam = test::look_at(target + vec3(0.0f, 0.05f, 0.015f), target, 0.01f);
      const FrameImage img = render_frame(scene, make_camera(cam, st.width, st.height, {}), st).image;
      // One light per sample: 16,384 samples of a ratio whose spread the tree keeps small.
      const double tolerance = use == LightTreeUse::On ? 1e-2 : 2e-3;
      EXPECT_NEAR(test::stats_of(img).mean, expected, tolerance * expected)
          << (use == LightTreeUse::On ? "tree" : "every light") << " at " << target.x << "," << target.z;
    }
  }
}

}  // namespace
}  // namespace tessera
