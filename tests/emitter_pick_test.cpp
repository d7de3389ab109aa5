// The pilot that sets how often a vertex samples an emitter (renderer/integrator/emitter_pick.h):
// its estimate of the emitters' share of the direct light against the same share integrated in
// closed form (Lambert's polygon formula) over the same camera rays' hits.
#include <gtest/gtest.h>

#include <cmath>

#include "renderer/integrator/emitter_pick.h"
#include "tests/scene_builders.h"

namespace tessera {
namespace {

constexpr float kHalfSide = 0.25f, kHeight = 1.0f;

// A diffuse floor (y = 0, +-5) under a square emitter of radiance `le` facing down from y = 1
// (facing up, away from the floor, with `facing_up`).
SceneDescription floor_and_emitter(float le, bool facing_up = false) {
  SceneDescription s;
  test::add_mesh(s, test::make_quad({0, 0, 0}, {5, 0, 0}, {0, 0, -5}, test::add_material(s, test::diffuse(vec3(0.5f)))));
  const vec3 u(kHalfSide, 0, 0), v(0, 0, facing_up ? -kHalfSide : kHalfSide);
  test::add_mesh(s, test::make_quad({0, kHeight, 0}, u, v, test::add_material(s, test::emitter(vec3(le)))));
  return s;
}

RenderScene make_scene(SceneDescription s, float sky) {
  EnvironmentParams env;
  env.background = vec3(sky);
  return RenderScene(std::move(s), env);
}

// The view of the floor the pilot looks at: below the emitter, which no camera ray meets.
RenderCamera camera_of(const RenderScene& rs) { return rs.camera(test::look_at({0, 0.6f, 2.5f}, {0, 0, 0}, 40.0f), 64, 64, {}); }

// The form factor from a point of the floor (normal +y) to the emitter square: Lambert's
// polygon formula, (1 / 2 pi) sum over edges of the angle they subtend times the cosine of
// their plane's normal with the floor's.
double form_factor_to_emitter(const glm::dvec3& x) {
  const double a = kHalfSide;
  const glm::dvec3 corners[4] = {{-a, kHeight, -a}, {a, kHeight, -a}, {a, kHeight, a}, {-a, kHeight, a}};
  double sum = 0.0;
  for (int i = 0; i < 4; ++i) {
    const glm::dvec3 r0 = glm::normalize(corners[i] - x), r1 = glm::normalize(corners[(i + 1) % 4] - x);
    const double angle = std::acos(std::clamp(glm::dot(r0, r1), -1.0, 1.0));
    sum += angle * glm::normalize(glm::cross(r0, r1)).y;
  }
  return std::fabs(sum) / (2.0 * kPi);
}

// What the pilot estimates, in closed form: over the grid's camera rays that meet the floor,
// the emitter's irradiance (pi le F) against the sky's (pi sky (1 - F): the emitter's back hides
// its part), summed, then as a probability (share / full_share, at least the floor, at most 1).
double expected_pick(const RenderScene& rs, const RenderCamera& camera, float le, float sky, const EmitterPickParams& p) {
  double emitters = 0.0, background = 0.0;
  for (int j = 0; j < p.grid; ++j)
    for (int i = 0; i < p.grid; ++i) {
      const Ray ray = camera.generate_ray({(i + 0.5f) / p.grid, (j + 0.5f) / p.grid}, vec2(0.5f), 0.0f);
      const glm::dvec3 o = glm::dvec3(ray.origin) + glm::dvec3(rs.origin), d(ray.direction);
      if (!(d.y < 0.0)) continue;
      const glm::dvec3 x = o - d * (o.y / d.y);
      if (std::fabs(x.x) > 5.0 || std::fabs(x.z) > 5.0) continue;
      const double f = form_factor_to_emitter(x);
      emitters += le * f;
      background += sky * (1.0 - f);
    }
  return std::clamp(emitters / (emitters + background) / p.full_share, static_cast<double>(p.floor), 1.0);
}

TEST(EmitterPick, MatchesTheDirectLightShareInClosedForm) {
  const EmitterPickParams params;
  for (float le : {1.0f, 3.0f, 30.0f}) {
    SCOPED_TRACE(le);
    const RenderScene rs = make_scene(floor_and_emitter(le), 1.0f);
    const RenderCamera camera = camera_of(rs);
    const double expected = expected_pick(rs, camera, le, 1.0f, params);
    EXPECT_NEAR(emitter_pick_probability(rs, camera, params), expected, 0.015 * expected);  // measured within 0.4%
    if (le == 30.0f) EXPECT_EQ(expected, 1.0);  // the emitter dominates: every vertex samples it
    else EXPECT_LT(expected, 0.9);  // else a share, in proportion
  }
}

TEST(EmitterPick, EveryVertexSamplesTheEmittersWhenNothingCompetes) {
  const RenderScene black = make_scene(floor_and_emitter(1.0f), 0.0f);
  EXPECT_EQ(emitter_pick_probability(black, camera_of(black)), 1.0f);
  SceneDescription no_emitter;
  test::add_mesh(no_emitter, test::make_quad({0, 0, 0}, {5, 0, 0}, {0, 0, -5}, test::add_material(no_emitter, test::diffuse(vec3(0.5f)))));
  const RenderScene white = make_scene(std::move(no_emitter), 1.0f);
  EXPECT_EQ(emitter_pick_probability(white, camera_of(white)), 1.0f);
}

// An emitter that faces away from everything the camera sees lights none of it: the floor.
TEST(EmitterPick, AnEmitterThatLightsNothingSeenIsSampledAtTheFloor) {
  const RenderScene rs = make_scene(floor_and_emitter(100.0f, true), 1.0f);
  EmitterPickParams params;
  EXPECT_EQ(emitter_pick_probability(rs, camera_of(rs), params), params.floor);
  params.floor = 0.2f;
  EXPECT_EQ(emitter_pick_probability(rs, camera_of(rs), params), 0.2f);
}

}  // namespace
}  // namespace tessera
