// Whole renders of analytic scenes whose exact images are known in closed form.
#include <gtest/gtest.h>

#include <cmath>

#include "renderer/render/render.h"
#include "tests/pixel_stats.h"
#include "tests/scene_builders.h"

namespace tessera {
namespace {

using test::add_material;
using test::add_mesh;

RenderResult render(SceneDescription scene, const Camera& cam, RenderSettings s, vec3 background,
                    CameraParams lens = {}) {
  EnvironmentParams env;
  env.background = background;
  RenderScene rs(std::move(scene), env);
  return render_frame(rs, rs.camera(cam, s.width, s.height, lens), s);
}

using test::PixelStats;
using test::stats_of;

// White furnace: a diffuse sphere of albedo 1 under a uniform environment of radiance 1.
// Every path sees the environment with throughput exactly 1 (cosine-weighted sampling of
// a Lambertian BSDF has weight = albedo), so every pixel, sphere or background, is 1;
// only float rounding of the throughput remains.
TEST(RenderClosedForm, WhiteFurnaceSphereIsOneEverywhere) {
  SceneDescription scene;
  const int white = add_material(scene, test::diffuse(vec3(1.0f)));
  add_mesh(scene, test::make_sphere(vec3(0.0f), 1.0f, 4, white));
  RenderSettings s;
  s.width = s.height = 48;
  s.spp = 16;
  s.max_bounces = 16;
  const RenderResult r = render(scene, test::look_at({0, 0, 4}, {0, 0, 0}, 40.0f), s, vec3(1.0f));
  for (float v : r.image.rgb) ASSERT_NEAR(v, 1.0f, 1e-5f);
  EXPECT_EQ(r.stats.dropped_samples, 0u);
}

// The furnace, whole renders: in a uniform white background of 1 every lossless
// material renders 1, however rough. Single-scattering GGX gave 0.40 for the white metal at
// roughness 1 and 0.60 for the rough glass sphere (centre 32x32 of 64x64); energy
// compensation must bring each within 1% (and Russian roulette adds no bias).
TEST(RenderClosedForm, WhiteFurnaceRoughMetalGlassAndCoatAreOne) {
  Material metal;  // the glTF default: white, metallic 1, roughness 1
  Material glass = test::diffuse(vec3(1.0f));
  glass.specular_factor = 1.0f;
  glass.transmission_factor = 1.0f;
  glass.roughness_factor = 0.7f;
  glass.thickness_factor = 1.0f;  // a volume: refraction in and out
  Material thin = glass;
  thin.thickness_factor = 0.0f;
  Material coated = test::diffuse(vec3(1.0f));
  coated.specular_factor = 1.0f;
  coated.roughness_factor = 0.5f;
  coated.clearcoat_factor = 1.0f;
  coated.clearcoat_roughness_factor = 0.6f;
  Material prism_glass = glass;  // KHR_materials_dispersion: each path picks a wavelength
  prism_glass.dispersion = 2.0f;
  const std::pair<const char*, Material> cases[] = {{"metal roughness 1", metal},
                                                    {"glass roughness 0.7", glass},
                                                    {"thin glass", thin},
                                                    {"clear coat", coated},
                                                    {"dispersive glass", prism_glass}};
  for (const auto& [name, material] : cases) {
    SceneDescription scene;
    add_mesh(scene, test::make_sphere(vec3(0.0f), 1.0f, 4, add_material(scene, material)));
    RenderSettings s;
    s.width = s.height = 64;
    // The glass's mean settles within 0.4% of 1 from 128 spp (0.99 at 64); a dispersive path's
    // wavelength weight (up to 3 in a channel) needs 1024 for 1% per channel (0.2% at 4096).
    s.spp = material.dispersion > 0.0f ? 1024 : 128;
    s.max_bounces = 256;  // paths trapped by total internal reflection need many
    const RenderResult r = render(scene, test::look_at({0, 0, 4}, {0, 0, 0}, 40.0f), s, vec3(1.0f));
    glm::dvec3 sum(0.0);  // per channel: a wavelength-sampled path must stay white on average
    for (int y = 16; y < 48; ++y)
      for (int x = 16; x < 48; ++x)
        for (int c = 0; c < 3; ++c) sum[c] += r.image.rgb[3 * (y * 64 + x) + c];
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c] / (32 * 32), 1.0, 0.01) << name << ", channel " << c;
  }
}

// Smooth, lossless glass in the furnace: at each interface a path reflects or refracts with
// the Fresnel odds and keeps a weight near 1, but entering the glass scales radiance, and so
// the throughput, by 1/eta^2 (0.44). Russian roulette (from the fifth bounce) must look past
// that scale, as it would otherwise end paths inside the third of three spheres in a row and
// weigh the survivors up: each centre pixel, whose samples all pass the three, is 1 with
// little spread, not just on average.
TEST(RenderClosedForm, SmoothGlassInTheFurnaceIsOneWithoutRouletteNoise) {
  Material glass = test::diffuse(vec3(1.0f));
  glass.specular_factor = 1.0f;
  glass.transmission_factor = 1.0f;
  glass.roughness_factor = 0.0f;
  glass.thickness_factor = 1.0f;  // a volume: refraction in and out
  SceneDescription scene;
  const int m = add_material(scene, glass);
  for (int k = 0; k < 3; ++k) add_mesh(scene, test::make_sphere(vec3(0.0f, 0.0f, -3.0f * k), 1.0f, 4, m));
  RenderSettings s;
  s.width = s.height = 64;
  s.spp = 16;
  s.max_bounces = 64;
  const RenderResult r = render(scene, test::look_at({0, 0, 4}, {0, 0, 0}, 10.0f), s, vec3(1.0f));
  double sum = 0.0, squares = 0.0;
  for (int y = 24; y < 40; ++y)
    for (int x = 24; x < 40; ++x) {
      const double v = r.image.rgb[3 * (y * 64 + x)];
      sum += v;
      squares += (v - 1.0) * (v - 1.0);
    }
  EXPECT_NEAR(sum / 256, 1.0, 0.01);
  // Measured: RMS 0.0057 from 1; 0.107 with roulette seeing the 1/eta^2 (the mean 1 either way).
  EXPECT_LT(std::sqrt(squares / 256), 0.02);
}

// Inside a closed sphere whose wall has albedo a and emits Le (front faces inward), every
// path gathers Le at each of its vertices, weighted by a^k after k bounces:
// L = Le (1 - a^(B+1)) / (1 - a) with at most B bounces. Light sampling (the wall is the
// light) and Russian roulette add noise but no bias: the image mean must match within the
// standard error that the pixels' own spread gives.
SceneDescription glowing_enclosure(float albedo, float le) {
  SceneDescription scene;
  Material wall = test::diffuse(vec3(albedo));
  wall.emissive_factor = vec3(le);
  add_mesh(scene, test::make_sphere(vec3(0.0f), 5.0f, 3, add_material(scene, wall), /*inward=*/true));
  return scene;
}

void expect_enclosure_mean(float albedo, int max_bounces) {
  RenderSettings s;
  s.width = s.height = 64;
  s.spp = 16;
  s.max_bounces = max_bounces;
  const RenderResult r = render(glowing_enclosure(albedo, 1.0f), test::look_at({0, 0, 0}, {0, 0, -1}, 60.0f), s, vec3(0));
  const double expected = (1.0 - std::pow(albedo, max_bounces + 1)) / (1.0 - albedo);
  const PixelStats st = stats_of(r.image);
  // The pixels are independent estimates: the image mean has standard error sqrt(var / n).
  const double stderr_mean = std::sqrt(st.variance / (s.width * s.height));
  EXPECT_GT(st.variance, 0.0);  // the estimators really were stochastic
  EXPECT_LT(stderr_mean, 0.01 * expected);  // and the test is sharp enough to mean something
  EXPECT_NEAR(st.mean, expected, 5.0 * stderr_mean) << "albedo " << albedo << ", bounces " << max_bounces;
}

TEST(RenderClosedForm, EnclosureWithTwoBouncesMatchesTheSeries) { expect_enclosure_mean(0.5f, 2); }

TEST(RenderClosedForm, EnclosureWithRussianRouletteIsUnbiased) { expect_enclosure_mean(0.8f, 64); }

// An emissive quad filling the view, seen head-on: every pixel is its radiance, exactly,
// whatever the bounce limit (black diffuse surface, black background).
TEST(RenderClosedForm, EmissiveQuadHeadOnRendersItsRadiance) {
  SceneDescription scene;
  Material m = test::emitter(vec3(0.25f, 0.5f, 0.75f));
  m.emissive_strength = 4.0f;
  add_mesh(scene, test::make_quad({0, 0, 0}, {10, 0, 0}, {0, 10, 0}, add_material(scene, m)));
  RenderSettings s;
  s.width = s.height = 16;
  s.spp = 4;
  const RenderResult r = render(scene, test::look_at({0, 0, 3}, {0, 0, 0}, 30.0f), s, vec3(0));
  for (std::size_t i = 0; i < r.image.rgb.size(); i += 3) {
    ASSERT_FLOAT_EQ(r.image.rgb[i + 0], 1.0f);
    ASSERT_FLOAT_EQ(r.image.rgb[i + 1], 2.0f);
    ASSERT_FLOAT_EQ(r.image.rgb[i + 2], 3.0f);
  }
}

// The same quad seen from behind: single-sided emission shows black, double-sided shows it.
TEST(RenderClosedForm, SingleSidedEmitterIsDarkFromBehind) {
  for (bool double_sided : {false, true}) {
    SceneDescription scene;
    Material m = test::emitter(vec3(1.0f));
    m.double_sided = double_sided;
    add_mesh(scene, test::make_quad({0, 0, 0}, {10, 0, 0}, {0, 10, 0}, add_material(scene, m)));
    RenderSettings s;
    s.width = s.height = 8;
    s.spp = 1;
    const RenderResult r = render(scene, test::look_at({0, 0, -3}, {0, 0, 0}, 30.0f), s, vec3(0));
    for (float v : r.image.rgb) ASSERT_EQ(v, double_sided ? 1.0f : 0.0f);
  }
}

// A diffuse floor under a square emitter against the parallel-rectangle form factor
// (test::floor_under_square_emitter), the whole scene `lift` above the origin. One bounce:
// direct light only, found by light sampling and BSDF sampling together (MIS). Under a uniform
// `sky` the floor sees it too, but for the emitter's solid angle, whose back (black) hides it:
// albedo Lsky (1 - 4F). `pick`: the probability a vertex samples the emitter (0: the pilot's).
void expect_floor_under_square_emitter(float lift, bool animated = false, float sky = 0.0f, float pick = 0.0f) {
  const float a = 0.25f, h = 1.0f, le = 4.0f, albedo = 0.5f;
  SceneDescription scene;
  scene.animated = animated;
  add_mesh(scene, test::make_quad({0, lift, 0}, {5, 0, 0}, {0, 0, -5}, add_material(scene, test::diffuse(vec3(albedo)))));
  add_mesh(scene, test::make_quad({0, lift + h, 0}, {a, 0, 0}, {0, 0, a}, add_material(scene, test::emitter(vec3(le)))));
  RenderSettings s;
  s.width = s.height = 5;  // the centre pixel looks at the origin through a 0.01 degree field
  s.spp = 4096;
  s.max_bounces = 1;
  s.emitter_pick = pick;
  const RenderResult r = render(scene, test::look_at({0, lift + 0.5f, 3}, {0, lift, 0}, 0.01f), s, vec3(sky));
  const double expected = test::floor_under_square_emitter(a, h, le, albedo) +
                          sky * (albedo - test::floor_under_square_emitter(a, h, 1.0, albedo));
  // The floor is seen at 9.5 degrees, so the footprint is 6x longer than wide: over 0.1 degree
  // (+-16 mm along) the irradiance fell by 1.5e-4 on average, at 0.01 degree by ~1e-6.
  const PixelStats st = stats_of(r.image);
  const double stderr_pixel = std::sqrt(st.variance + 1e-12);  // spread between pixels = per-pixel noise
  EXPECT_NEAR(st.mean, expected, 4.0 * stderr_pixel / std::sqrt(25.0) + 1e-4 * expected);
  EXPECT_LT(stderr_pixel, 0.02 * expected);
}

TEST(RenderClosedForm, FloorUnderASquareEmitterMatchesTheFormFactor) { expect_floor_under_square_emitter(0.0f); }

// Under a white sky the pilot has the emitter sampled at a share of the vertices
// (integrator/emitter_pick.h); at that share, at one in ten and at every vertex the floor
// shows the same light: the estimate is divided by the probability, and MIS knows it.
TEST(RenderClosedForm, FloorUnderASquareEmitterAndASkyMatchesTheFormFactorHoweverOftenTheEmitterIsSampled) {
  for (float pick : {0.0f, 0.1f, 1.0f}) {
    SCOPED_TRACE(pick);
    expect_floor_under_square_emitter(0.0f, false, 1.0f, pick);
  }
}

// The same 100 units up, where a ray origin's offset off its surface (256 ulps of each
// coordinate: 2e-3 there) exceeds the shadow ray's tolerance before the light (1e-4 of the
// distance): a shadow ray aimed from the moved origin along the unmoved direction met the
// emitter's own plane early and was stopped by it, and the floor lost its light-sampled part
// (it rendered 0.0008 for 0.147). The offset itself still moves the BSDF-sampled rays' origins
// 2 mm towards the light: 6e-5 too bright here, within the 1e-4 allowed.
TEST(RenderClosedForm, FloorUnderASquareEmitterFarFromTheOriginMatchesTheFormFactor) {
  expect_floor_under_square_emitter(100.0f);
}

// 10,000 units up, where floats are 1e-3 apart and rays would leave the floor 0.25 above it
// (a quarter of the way to the light): it is rendered about its centre (render_origin.h).
TEST(RenderClosedForm, FloorUnderASquareEmitterTenThousandUnitsUpMatchesTheFormFactor) {
  expect_floor_under_square_emitter(1e4f);
}

// The same as a frame of an animation: rendered about the nearest corner of its grid of
// 64-unit cells (8 times its size, rounded up to a power of two), 16.5 units below it.
TEST(RenderClosedForm, FloorUnderASquareEmitterTenThousandUnitsUpInAnAnimationMatchesTheFormFactor) {
  expect_floor_under_square_emitter(1e4f, true);
}

// KHR_materials_diffuse_transmission: a sheet with no specular layer (pure Lambert), base
// colour b, transmitting a share t of its diffuse light with colour c, under a uniform
// background of 1: it shows (1 - t) b (reflected) + t c (transmitted from behind). A sample
// picks reflection or transmission at random (then carries exactly what that side gives over
// its probability), so pixels scatter about the value: the image mean within 0.3%.
TEST(RenderClosedForm, DiffuseTransmissionSheetShowsReflectedPlusTransmitted) {
  const vec3 b(0.2f, 0.4f, 0.6f), c(1.0f, 0.5f, 0.25f);
  const float t = 0.75f;
  Material sheet = test::diffuse(b);
  sheet.diffuse_transmission_factor = t;
  sheet.diffuse_transmission_color_factor = c;
  SceneDescription scene;
  add_mesh(scene, test::make_quad({0, 0, 0}, {10, 0, 0}, {0, 10, 0}, add_material(scene, sheet)));
  RenderSettings s;
  s.width = s.height = 8;
  s.spp = 256;
  s.max_bounces = 2;
  const RenderResult r = render(scene, test::look_at({0, 0, 3}, {0, 0, 0}, 30.0f), s, vec3(1.0f));
  const vec3 expected = (1.0f - t) * b + t * c;
  for (int k = 0; k < 3; ++k) {
    const PixelStats st = stats_of(r.image, k);
    EXPECT_NEAR(st.mean, expected[k], 3e-3 * expected[k]) << "channel " << k;
  }
}

// The same floor and light with a thin glass pane between them (smooth, ior 1.5, thin-walled
// transmission 1). Near normal incidence the pane passes 1 - F0 = 1 - 0.04 of the light
// (Schlick's term at the light's widest angle here, 19 degrees, adds under 1e-5), so the
// floor shows the form factor times 0.96. Shadow rays pass the pane with that transmittance,
// so light sampling and BSDF sampling (through the pane's straight pass) agree on it, and
// with both the floor is far less noisy than by BSDF sampling alone, which is what tessera
// had while shadow rays stopped at glass.
TEST(RenderClosedForm, ThinGlassPaneTransmitsTheFormFactorTimesOneMinusF0) {
  const float a = 0.25f, h = 1.0f, le = 4.0f, albedo = 0.5f;
  SceneDescription scene;
  add_mesh(scene, test::make_quad({0, 0, 0}, {5, 0, 0}, {0, 0, -5}, add_material(scene, test::diffuse(vec3(albedo)))));
  add_mesh(scene, test::make_quad({0, h, 0}, {a, 0, 0}, {0, 0, a}, add_material(scene, test::emitter(vec3(le)))));
  Material glass = test::diffuse(vec3(1.0f));
  glass.specular_factor = 1.0f;
  glass.roughness_factor = 0.0f;
  glass.transmission_factor = 1.0f;  // no thickness: thin-walled
  add_mesh(scene, test::make_quad({0, 0.75f, 0}, {0.6f, 0, 0}, {0, 0, 0.6f}, add_material(scene, glass)));
  const double expected = test::floor_under_square_emitter(a, h, le, albedo) * (1.0 - 0.04);
  PixelStats by_mode[2];
  for (const LightSampling mode : {LightSampling::Mis, LightSampling::BsdfOnly}) {
    RenderSettings s;
    s.width = s.height = 5;
    s.spp = 1024;
    s.max_bounces = 1;
    s.light_sampling = mode;
    const RenderResult r = render(scene, test::look_at({0, 0.5f, 3}, {0, 0, 0}, 0.01f), s, vec3(0));
    const PixelStats st = stats_of(r.image);
    const double stderr_mean = std::sqrt(st.variance / 25.0);
    EXPECT_NEAR(st.mean, expected, 4.0 * stderr_mean + 2e-3 * expected) << (mode == LightSampling::Mis ? "mis" : "bsdf");
    by_mode[mode == LightSampling::Mis ? 0 : 1] = st;
  }
  EXPECT_GT(by_mode[1].variance, 10.0 * by_mode[0].variance);
}

}  // namespace
}  // namespace tessera
