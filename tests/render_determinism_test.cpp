// The image depends only on the scene, the settings and the seed: never on the thread
// count or the tile size. Bit for bit.
#include <gtest/gtest.h>


#include <glm/gtc/matrix_transform.hpp>

#include "renderer/render/render.h"
#include "tests/same_bits.h"
#include "tests/scene_builders.h"

namespace tessera {
namespace {

// A small room with a sphere, an emitter and a point light, open at the front and right to a
// bright background: long paths, Russian roulette, shadow rays, instancing and emitters sampled
// at a share of the vertices (the background competes with them) all take part.
RenderScene& room() {
  static RenderScene* scene = [] {
    SceneDescription d;
    const int white = test::add_material(d, test::diffuse(vec3(0.7f)));
    const int red = test::add_material(d, test::diffuse(vec3(0.7f, 0.1f, 0.1f)));
    const int light = test::add_material(d, test::emitter(vec3(8.0f)));
    test::add_mesh(d, test::make_quad({0, -1, 0}, {1, 0, 0}, {0, 0, -1}, white));  // floor, facing up
    test::add_mesh(d, test::make_quad({0, 1, 0}, {1, 0, 0}, {0, 0, 1}, white));  // ceiling
    test::add_mesh(d, test::make_quad({0, 0, -1}, {1, 0, 0}, {0, 1, 0}, white));  // back wall
    test::add_mesh(d, test::make_quad({-1, 0, 0}, {0, 0, 1}, {0, 1, 0}, red));  // left wall
    test::add_mesh(d, test::make_quad({0, 0.99f, 0}, {0.3f, 0, 0}, {0, 0, 0.3f}, light));  // facing down
    test::add_mesh(d, test::make_sphere({0, 0, 0}, 0.25f, 2, white),
                   {glm::translate(glm::mat4(1.0f), {-0.4f, -0.7f, 0.2f}), glm::translate(glm::mat4(1.0f), {0.4f, -0.7f, -0.3f})});
    PunctualLight point;
    point.position = {0.5f, 0.5f, 0.5f};
    point.intensity = 2.0f;
    d.lights.push_back(point);
    for (int i = 0; i < 12; ++i) {  // a row of small lights along the ceiling: the light tree's
      PunctualLight small;
      small.position = {-0.9f + 0.15f * i, 0.9f, -0.5f + 0.08f * i};
      small.intensity = 0.05f;
      d.lights.push_back(small);
    }
    EnvironmentParams env;
    env.background = vec3(2.0f);
    return new RenderScene(std::move(d), env);
  }();
  return *scene;
}

FrameImage render_with(int threads, int tile_size, LightTreeUse light_tree = LightTreeUse::Off) {
  RenderSettings s;
  s.width = 61;  // not a multiple of any tile size: partial tiles too
  s.height = 47;
  s.spp = 7;  // waves of 1, 2, 4
  s.max_bounces = 12;
  s.threads = threads;
  s.tile_size = tile_size;
  s.seed = 1234;
  s.aovs = {true, true, true};
  s.light_tree = light_tree;
  const RenderCamera cam = make_camera(test::look_at({0, 0, 3}, {0, 0, 0}, 45.0f), s.width, s.height, {0.0f, 0.05f, 3.0f});
  return render_frame(room(), cam, s).image;
}

// The room's background competes with its emitter: the pilot of emitter sampling
// (integrator/emitter_pick.h) runs, and has the emitter sampled at a share of the vertices.
TEST(RenderDeterminism, TheRoomSamplesItsEmitterAtAShareOfTheVertices) {
  RenderSettings s;
  s.width = s.height = 8;
  s.spp = 1;
  const RenderCamera cam = make_camera(test::look_at({0, 0, 3}, {0, 0, 0}, 45.0f), s.width, s.height, {0.0f, 0.05f, 3.0f});
  const float pick = render_frame(room(), cam, s).stats.emitter_pick;
  EXPECT_GT(pick, 0.05f);
  EXPECT_LT(pick, 1.0f);
}

TEST(RenderDeterminism, OneThreadAndTwoThreadsGiveTheSameBits) {
  test::expect_same_image(render_with(1, 32), render_with(2, 32));
}

TEST(RenderDeterminism, TileSize8And64GiveTheSameBits) {
  test::expect_same_image(render_with(2, 8), render_with(2, 64));
}

// With one punctual light a vertex chosen from the light tree: its own draw of the sampler.
TEST(RenderDeterminism, OneThreadAndTwoThreadsGiveTheSameBitsWithTheLightTree) {
  test::expect_same_image(render_with(1, 32, LightTreeUse::On), render_with(2, 32, LightTreeUse::On));
}

TEST(RenderDeterminism, TileSize8And64GiveTheSameBitsWithTheLightTree) {
  test::expect_same_image(render_with(2, 8, LightTreeUse::On), render_with(2, 64, LightTreeUse::On));
}

// A floor and a sphere under 16 x 16 small emissive squares (512 triangles), some one-sided
// facing down, some double-sided and tilted: the emitters' light tree chooses each vertex's
// triangle, and the MIS weight at an emitter hit walks it again from the previous vertex.
RenderScene& under_many_emitters() {
  static RenderScene* scene = [] {
    SceneDescription d;
    const int white = test::add_material(d, test::diffuse(vec3(0.7f)));
    test::add_mesh(d, test::make_quad({0, -1, 0}, {2, 0, 0}, {0, 0, -2}, white));
    test::add_mesh(d, test::make_sphere({0, -0.6f, 0}, 0.4f, 2, white));
    Material one_sided = test::emitter(vec3(3.0f)), two_sided = test::emitter(vec3(1.0f, 2.0f, 4.0f));
    two_sided.double_sided = true;
    const int a = test::add_material(d, one_sided), b = test::add_material(d, two_sided);
    for (int row = 0; row < 16; ++row)
      for (int col = 0; col < 16; ++col) {
        const bool tilted = (row + col) % 5 == 0;
        test::add_mesh(d, test::make_quad({-1.5f + 0.2f * col, 0.8f, -1.5f + 0.2f * row}, {0.04f, tilted ? 0.03f : 0.0f, 0},
                                          {0, 0, 0.04f}, tilted ? b : a));
      }
    return new RenderScene(std::move(d), EnvironmentParams{});
  }();
  return *scene;
}

RenderResult render_emitters_with(int threads, int tile_size) {
  RenderSettings s;
  s.width = 61;
  s.height = 47;
  s.spp = 7;
  s.max_bounces = 6;
  s.threads = threads;
  s.tile_size = tile_size;
  s.seed = 99;
  s.aovs = {true, true, true};
  s.light_tree = LightTreeUse::On;
  const RenderCamera cam = make_camera(test::look_at({0, 0.5f, 3}, {0, -0.5f, 0}, 50.0f), s.width, s.height, {});
  return render_frame(under_many_emitters(), cam, s);
}

TEST(RenderDeterminism, OneThreadAndTwoThreadsGiveTheSameBitsWithTheEmitterTree) {
  const RenderResult one = render_emitters_with(1, 32);
  EXPECT_EQ(one.stats.emitter_tree_triangles, 512u);
  test::expect_same_image(one.image, render_emitters_with(2, 32).image);
}

TEST(RenderDeterminism, TileSize8And64GiveTheSameBitsWithTheEmitterTree) {
  test::expect_same_image(render_emitters_with(2, 8).image, render_emitters_with(2, 64).image);
}

TEST(RenderDeterminism, ADifferentSeedGivesADifferentImage) {
  FrameImage a = render_with(2, 16);
  RenderSettings s;
  EXPECT_FALSE(test::same_bits(a.rgb, std::vector<float>(a.rgb.size(), 0.0f)));  // something was lit
  // Same settings but another seed must change the noise.
  s.width = 61;
  s.height = 47;
  s.spp = 7;
  s.max_bounces = 12;
  s.seed = 4321;
  const RenderCamera cam = make_camera(test::look_at({0, 0, 3}, {0, 0, 0}, 45.0f), s.width, s.height, {0.0f, 0.05f, 3.0f});
  EXPECT_FALSE(test::same_bits(a.rgb, render_frame(room(), cam, s).image.rgb));
}

}  // namespace
}  // namespace tessera
