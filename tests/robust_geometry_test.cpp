// Geometry that breaks naive code, in scenes built directly (no loader in between, so the
// renderer itself must cope): degenerate and zero-area triangles, zero-length normals,
// coincident surfaces, huge and tiny scales, and non-finite emission. No NaN reaches a
// pixel, non-finite samples are dropped and counted, and a diffuse plane under a directional
// or point light renders its closed form albedo/pi * E * cos at every scale: a shadow ray
// that hit the surface it leaves (self-intersection "acne") would make pixels black.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "renderer/render/render.h"
#include "tests/pixel_stats.h"
#include "tests/scene_builders.h"

namespace tessera {
namespace {

using test::add_material;
using test::add_mesh;

RenderResult render(SceneDescription scene, const Camera& cam, int size, int spp, int bounces = 1) {
  EnvironmentParams env;
  env.background = vec3(0.0f);
  RenderScene rs(std::move(scene), env);
  RenderSettings s;
  s.width = s.height = size;
  s.spp = spp;
  s.max_bounces = bounces;
  return render_frame(rs, rs.camera(cam, s.width, s.height, {}), s);
}

void expect_all_finite(const FrameImage& img) {
  for (float v : img.rgb) ASSERT_TRUE(std::isfinite(v));
}

// A floor quad of half side `half` at height y = 0, around `center`, facing up.
TriangleMesh floor_quad(vec3 center, float half, int material) {
  return test::make_quad(center, {half, 0, 0}, {0, 0, -half}, material);
}

// ---- degenerate input ---------------------------------------------------------------------

// Zero-area triangles (a repeated vertex, three collinear vertices, a sliver of 1e-30) next
// to a real floor: they are never hit (or hit harmlessly), so the image is the same bit for
// bit as the floor alone, with nothing dropped.
TEST(RobustGeometry, ZeroAreaTrianglesChangeNothing) {
  auto scene_with = [](bool degenerate) {
    SceneDescription scene;
    const int white = add_material(scene, test::diffuse(vec3(0.8f)));
    add_mesh(scene, floor_quad({0, 0, 0}, 2.0f, white));
    if (degenerate) {
      TriangleMesh m;
      m.positions = {{0, 0.5f, 0}, {0, 0.5f, 0}, {1, 0.5f, 0},  // repeated vertex
                     {-1, 0.3f, 0}, {0, 0.3f, 0}, {1, 0.3f, 0},  // collinear
                     {0, 0.2f, 0}, {1, 0.2f, 0}, {0.5f, 0.2f, 1e-30f}};  // a sliver
      m.indices = {0, 1, 2, 3, 4, 5, 6, 7, 8};
      m.material = white;
      add_mesh(scene, m);
    }
    PunctualLight sun;
    sun.type = PunctualLight::Type::Directional;
    sun.direction = glm::normalize(vec3(0.3f, -1.0f, 0.2f));
    sun.intensity = 3.0f;
    scene.lights.push_back(sun);
    return scene;
  };
  const Camera cam = test::look_at({0, 2, 2}, {0, 0, 0}, 50.0f);
  const RenderResult with = render(scene_with(true), cam, 32, 4, 4);
  const RenderResult without = render(scene_with(false), cam, 32, 4, 4);
  expect_all_finite(with.image);
  EXPECT_EQ(with.stats.dropped_samples, 0u);
  EXPECT_EQ(std::memcmp(with.image.rgb.data(), without.image.rgb.data(), with.image.rgb.size() * sizeof(float)), 0);
}

// Vertex normals of zero length (and NaN ones) cannot be normalised: the surface must fall
// back to its geometric normal and shade like a flat floor.
TEST(RobustGeometry, ZeroLengthAndNanNormalsShadeAsTheFlatSurface) {
  const float albedo = 0.6f, lux = 2.0f;
  const vec3 to_light = glm::normalize(vec3(0.0f, 1.0f, 1.0f));
  for (const vec3 bad : {vec3(0.0f), vec3(std::nanf(""))}) {
    SceneDescription scene;
    TriangleMesh floor = floor_quad({0, 0, 0}, 2.0f, add_material(scene, test::diffuse(vec3(albedo))));
    floor.normals.assign(floor.positions.size(), bad);
    add_mesh(scene, floor);
    PunctualLight sun;
    sun.type = PunctualLight::Type::Directional;
    sun.direction = -to_light;
    sun.intensity = lux;
    scene.lights.push_back(sun);
    const RenderResult r = render(scene, test::look_at({0, 1, 0.01f}, {0, 0, 0}, 20.0f), 16, 2);
    const float expected = albedo / kPi * lux * to_light.y;
    for (float v : r.image.rgb) ASSERT_NEAR(v, expected, 1e-5f * expected) << "normal " << bad.x;
    EXPECT_EQ(r.stats.dropped_samples, 0u);
  }
}

// Two coincident floors (z-fighting) of albedos 0.2 and 0.8: each pixel sees one or the other
// (or a mix at a sample boundary), never NaN, never a self-shadowed black.
TEST(RobustGeometry, CoincidentSurfacesShadeAsOneOrTheOther) {
  SceneDescription scene;
  add_mesh(scene, floor_quad({0, 0, 0}, 2.0f, add_material(scene, test::diffuse(vec3(0.2f)))));
  add_mesh(scene, floor_quad({0, 0, 0}, 2.0f, add_material(scene, test::diffuse(vec3(0.8f)))));
  PunctualLight sun;
  sun.type = PunctualLight::Type::Directional;
  sun.direction = {0, -1, 0};
  sun.intensity = kPi;  // E = pi: the radiance is the albedo
  scene.lights.push_back(sun);
  const RenderResult r = render(scene, test::look_at({0, 1, 0.01f}, {0, 0, 0}, 40.0f), 24, 4);
  for (float v : r.image.rgb) {
    ASSERT_GE(v, 0.2f - 1e-5f);
    ASSERT_LE(v, 0.8f + 1e-5f);
  }
}

// Emission of infinite strength makes every sample that sees it infinite: each is dropped
// (the pixel keeps the mean of the others, here black) and counted.
TEST(RobustGeometry, NonFiniteSamplesAreDroppedAndCounted) {
  SceneDescription scene;
  Material hot = test::emitter(vec3(1.0f));
  hot.emissive_strength = std::numeric_limits<float>::infinity();
  add_mesh(scene, test::make_quad({0, 0, 0}, {10, 0, 0}, {0, 10, 0}, add_material(scene, hot)));
  const RenderResult r = render(scene, test::look_at({0, 0, 3}, {0, 0, 0}, 30.0f), 8, 3, 0);
  EXPECT_EQ(r.stats.dropped_samples, 8u * 8u * 3u);
  for (float v : r.image.rgb) ASSERT_EQ(v, 0.0f);
}

// A camera whose matrix is NaN (here: looking at its own position) gives NaN rays; each
// sample is dropped and counted instead of reaching Embree, which would abort the process.
TEST(RobustGeometry, NanCameraRaysAreDroppedNotTraced) {
  SceneDescription scene;
  add_mesh(scene, floor_quad({0, 0, 0}, 2.0f, add_material(scene, test::diffuse(vec3(0.5f)))));
  const RenderResult r = render(scene, test::look_at({0, 1, 0}, {0, 1, 0}, 40.0f), 4, 2);
  EXPECT_EQ(r.stats.dropped_samples, 4u * 4u * 2u);
  for (float v : r.image.rgb) ASSERT_EQ(v, 0.0f);
}

// ---- scale --------------------------------------------------------------------------------

struct ScaleCase {
  float scale;  // the whole scene, camera and light scaled by it
  float offset;  // and moved this far (in units of the scale) from the origin
};

void PrintTo(const ScaleCase& c, std::ostream* os) { *os << "scale " << c.scale << ", offset " << c.offset; }

class RobustScale : public testing::TestWithParam<ScaleCase> {};

// A diffuse floor (albedo a) lit by a directional light of E lux at 45 degrees: every pixel
// is a/pi * E * cos(45), exactly (one bounce, black background: only the light's direct term,
// which has no noise). A self-intersecting shadow ray would make a pixel 0.
TEST_P(RobustScale, DiffuseFloorUnderADirectionalLightMatchesTheClosedForm) {
  const float s = GetParam().scale, albedo = 0.5f, lux = 3.0f;
  const vec3 c(GetParam().offset * s, 0.0f, -GetParam().offset * s);
  SceneDescription scene;
  add_mesh(scene, floor_quad(c, 10.0f * s, add_material(scene, test::diffuse(vec3(albedo)))));
  PunctualLight sun;
  sun.type = PunctualLight::Type::Directional;
  sun.direction = glm::normalize(vec3(1.0f, -1.0f, 0.0f));
  sun.intensity = lux;
  scene.lights.push_back(sun);
  const RenderResult r = render(scene, test::look_at(c + vec3(0, 2 * s, 0.5f * s), c, 60.0f), 24, 2);
  const double expected = albedo / M_PI * lux * std::cos(M_PI / 4);
  int dark = 0;
  for (float v : r.image.rgb) dark += v < 0.5 * expected;
  EXPECT_EQ(dark, 0) << "pixels in their own shadow";
  for (float v : r.image.rgb) ASSERT_NEAR(v, expected, 1e-4 * expected);
  EXPECT_EQ(r.stats.dropped_samples, 0u);
}

// The same floor under a point light at height h straight above the image centre: the pixel
// there sees E = I / h^2 (cos = 1), so its radiance is a/pi * I / h^2. The light's intensity
// grows with the square of the scale, so the expected value is the same at every scale.
TEST_P(RobustScale, DiffuseFloorUnderAPointLightMatchesTheClosedForm) {
  const float s = GetParam().scale, albedo = 0.5f, h = 2.0f, intensity = 4.0f;
  const vec3 c(GetParam().offset * s, 0.0f, -GetParam().offset * s);
  SceneDescription scene;
  add_mesh(scene, floor_quad(c, 10.0f * s, add_material(scene, test::diffuse(vec3(albedo)))));
  PunctualLight bulb;
  bulb.position = c + vec3(0, h * s, 0);
  bulb.intensity = intensity * s * s;
  scene.lights.push_back(bulb);
  // Looking straight down from below the light through a 0.5 degree field: the floor seen
  // is flat to 1e-5 in irradiance.
  const RenderResult r = render(scene, test::look_at(c + vec3(0, 1.0f * s, 0.01f * s), c, 0.5f), 5, 2);
  const double expected = albedo / M_PI * intensity / (h * h);
  for (float v : r.image.rgb) ASSERT_NEAR(v, expected, 2e-4 * expected);
  EXPECT_EQ(r.stats.dropped_samples, 0u);
}

// The same floor under a square emitter (half-size a, height h, radiance Le): the pixel
// straight under its centre shows the parallel-rectangle form factor times albedo and Le at
// every scale, found by light sampling and BSDF sampling together (MIS). A shadow ray stopped
// by the emitter itself (or by the floor) would darken it; a ray origin moved too far off the
// floor would brighten it (at scale 1e-4 a fixed offset of 1/65536 was 15% of the light's
// height: +0.8%). The offsets here lie across the light's normal;
// RenderClosedForm.FloorUnderASquareEmitterFarFromTheOriginMatchesTheFormFactor moves the
// scene along it.
TEST_P(RobustScale, DiffuseFloorUnderASquareEmitterMatchesTheFormFactor) {
  const float s = GetParam().scale, albedo = 0.5f, a = 0.25f, h = 1.0f, le = 4.0f;
  const vec3 c(GetParam().offset * s, 0.0f, -GetParam().offset * s);
  // 1e5 away at scale 1 it is rendered about its centre (render_origin.h): its light samples
  // landed on the floats near 1e5, 64 across the light, before. The camera looks straight
  // down from exactly above c: a look-at matrix inverted in floats at 1e5 stood 2 cm off.
  SceneDescription scene;
  add_mesh(scene, floor_quad(c, 10.0f * s, add_material(scene, test::diffuse(vec3(albedo)))));
  add_mesh(scene, test::make_quad(c + vec3(0, h * s, 0), {a * s, 0, 0}, {0, 0, a * s}, add_material(scene, test::emitter(vec3(le)))));
  Camera down;
  down.camera_to_world = glm::mat4(vec4(1, 0, 0, 0), vec4(0, 0, -1, 0), vec4(0, 1, 0, 0), vec4(c + vec3(0, 0.5f * s, 0), 1));
  down.yfov = glm::radians(0.5f);
  const RenderResult r = render(scene, down, 5, 1024);
  const double expected = test::floor_under_square_emitter(a, h, le, albedo);
  const test::PixelStats st = test::stats_of(r.image);
  const double stderr_mean = std::sqrt(st.variance / 25.0 + 1e-14);  // 5x5 pixels, each its own noise
  EXPECT_NEAR(st.mean, expected, 4.0 * stderr_mean + 2e-4 * expected);
  EXPECT_EQ(r.stats.dropped_samples, 0u);
}

INSTANTIATE_TEST_SUITE_P(Scales, RobustScale,
                         testing::Values(ScaleCase{1e-6f, 0.0f}, ScaleCase{1e-4f, 0.0f}, ScaleCase{1e-4f, 100.0f},
                                         ScaleCase{1.0f, 0.0f}, ScaleCase{1.0f, 1e5f}, ScaleCase{1e5f, 0.0f},
                                         ScaleCase{1e5f, 10.0f}, ScaleCase{1e6f, 0.0f}),
                         [](const testing::TestParamInfo<ScaleCase>& info) {
                           std::string name = std::to_string(info.index) + "_scale_" +
                                              std::to_string(static_cast<int>(std::round(std::log10(info.param.scale))));
                           for (char& ch : name)
                             if (ch == '-') ch = 'm';
                           return name + "_offset_" + std::to_string(static_cast<long long>(info.param.offset));
                         });

}  // namespace
}  // namespace tessera
