// Path guiding (renderer/guiding/, integrator/guided_scattering.h, render/frame_guide.h): the
// guide's own densities, the guided mixture's sampling, what the guide learns, analytic
// scenes rendered guided, a caustic, and the determinism every render keeps.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <random>

#include "renderer/guiding/direction_tree.h"
#include "renderer/guiding/path_guide.h"
#include "renderer/integrator/guided_scattering.h"
#include "renderer/render/render.h"
#include "tests/chi_square.h"
#include "tests/pixel_stats.h"
#include "tests/same_bits.h"
#include "tests/scene_builders.h"

namespace tessera {
namespace {

using test::add_material;
using test::add_mesh;
using test::PixelStats;
using test::stats_of;

RenderResult render(SceneDescription scene, const Camera& cam, const RenderSettings& s, vec3 background) {
  EnvironmentParams env;
  env.background = background;
  RenderScene rs(std::move(scene), env);
  return render_frame(rs, rs.camera(cam, s.width, s.height, {}), s);
}

// A tree split to depth 3 (64 leaves) with random energies, a third of them zero.
DirectionTree uneven_tree() {
  DirectionTree flat;
  flat.set_energy({1.0});
  DirectionTree tree = flat.refined(0.01, 3);
  std::vector<double> energy(tree.size(), 0.0);
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (std::size_t n = 0; n < tree.size(); ++n)
    if (tree.is_leaf(static_cast<std::uint32_t>(n))) energy[n] = u(gen) < 0.3 ? 0.0 : std::pow(u(gen), 4.0);
  tree.set_energy(energy);
  return tree;
}

TEST(PathGuiding, DirectionTreeSamplesReportTheDensityItsPdfGives) {
  const DirectionTree tree = uneven_tree();
  std::mt19937 gen(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < 10000; ++i) {
    float pdf;
    const vec2 p = tree.sample({u(gen), u(gen)}, pdf);
    ASSERT_GT(pdf, 0.0f);
    ASSERT_NEAR(tree.pdf(p), pdf, 1e-4f * pdf) << p.x << " " << p.y;
  }
  // Where nothing was learnt the density is 0, not 0/0 (a NaN there once zeroed MIS weights).
  for (int i = 0; i < 10000; ++i) ASSERT_GE(tree.pdf({u(gen), u(gen)}), 0.0f);
}

// A guide over the unit box that learnt, in one round, light arriving from the upper half of
// the sphere (y > 0), fifty times as bright in the cone y > 0.9.
PathGuide trained_guide() {
  PathGuide guide(Bounds3{vec3(0.0f), vec3(1.0f)}, 1.0f);
  std::mt19937 gen(11);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < 200000; ++i) {
    const vec3 d = square_to_direction({u(gen), u(gen)});
    if (d.y > 0.0f) guide.record(vec3(u(gen), u(gen), u(gen)), d, d.y > 0.9f ? 50.0f : 1.0f);
  }
  guide.finish_round(1);
  return guide;
}

TEST(PathGuiding, GuideDirectionsHaveTheDensityItsPdfGivesAndItIntegratesToOne) {
  const PathGuide guide = trained_guide();
  const int region = guide.region(vec3(0.5f));
  ASSERT_GE(region, 0);
  std::mt19937 gen(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    float pdf;
    const vec3 d = guide.sample(region, {u(gen), u(gen)}, pdf);
    ASSERT_NEAR(guide.pdf(region, d), pdf, 1e-3f * pdf);
  }
  // Stratified over the square (equal solid angles): the density's integral over the sphere.
  double integral = 0.0;
  for (int i = 0; i < 512; ++i)
    for (int j = 0; j < 512; ++j)
      integral += guide.pdf(region, square_to_direction({(i + 0.5f) / 512, (j + 0.5f) / 512})) * 4.0 * kPi / (512 * 512);
  EXPECT_NEAR(integral, 1.0, 1e-3);
}

// The white diffuse surface (normal +y) whose directions the mixture draws in the tests below.
struct DiffuseVertex {
  ShadingPoint sp;
  Frame frame = Frame::from_normal({0.0f, 1.0f, 0.0f});
  vec3 wo;
  std::optional<GltfBsdf> bsdf;
  DiffuseVertex() {
    sp.base_color = vec3(1.0f);
    sp.metallic = 0.0f;
    sp.roughness = 1.0f;
    wo = frame.to_local(glm::normalize(vec3(0.3f, 1.0f, 0.2f)));
    bsdf.emplace(sp, wo, 1.5f, frame);
  }
};

// The guided mixture's directions against its own density (the guide's share of the guide's
// pdf plus the rest of the BSDF's): Pearson's chi-square over equal-solid-angle bins.
TEST(PathGuiding, GuidedMixtureSamplingMatchesItsPdf) {
  const PathGuide guide = trained_guide();
  const DiffuseVertex v;
  const GuideAt g = guide_at(&guide, vec3(0.5f), v.sp, *v.bsdf);
  ASSERT_TRUE(g.samples());
  ASSERT_GT(g.share, 0.3f);
  std::mt19937 gen(21);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const auto sample = [&](int) -> std::optional<vec3> {
    BsdfSample bs;
    if (!sample_guided(*v.bsdf, v.frame, v.wo, g, {u(gen), u(gen), u(gen)}, bs)) return std::nullopt;
    return bs.wi;
  };
  const auto pdf = [&](const vec3& wi) { return g.pdf(v.frame.to_world(wi), v.bsdf->pdf(v.wo, wi)); };
  const test::ChiSquareResult r = test::chi_square_test(sample, pdf, 200000);
  EXPECT_GT(r.p_value, 0.001) << "chi2 " << r.statistic << " dof " << r.dof;
  EXPECT_NEAR(r.pdf_integral, r.sampled_fraction, 0.01);
}

// The mixture's one-sample estimate of the light a white diffuse surface reflects from the
// cone y > 0.9 (radiance 1): the cone's projected solid angle over pi, 1 - 0.9^2 = 0.19, as
// the BSDF alone gives it (the white dielectric's specular layer reshapes it a little).
TEST(PathGuiding, GuidedMixtureEstimatesTheConesLightAsTheBsdfAlone) {
  const PathGuide guide = trained_guide();
  const DiffuseVertex v;
  const GuideAt guided = guide_at(&guide, vec3(0.5f), v.sp, *v.bsdf);
  double sums[2] = {0.0, 0.0};
  const int n = 400000;
  for (int k = 0; k < 2; ++k) {
    std::mt19937 gen(5 + k);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int i = 0; i < n; ++i) {
      BsdfSample bs;
      if (!sample_guided(*v.bsdf, v.frame, v.wo, k ? guided : GuideAt{}, {u(gen), u(gen), u(gen)}, bs)) continue;
      if (v.frame.to_world(bs.wi).y > 0.9f) sums[k] += bs.f.x * std::fabs(bs.wi.z) / bs.pdf / n;
    }
  }
  EXPECT_NEAR(sums[0], 0.19, 0.01);
  EXPECT_NEAR(sums[1], sums[0], 0.004);
}

// What the guide learns from records drawn by its own mixture (half uniform, half guide),
// round after round, of light from the cone y > 0.95 about a tilted axis: the guide's share of
// directions inside the cone grows from the cone's solid angle (2.5%) towards all of it.
TEST(PathGuiding, GuideLearnsWhereLightComesFrom) {
  PathGuide guide(Bounds3{vec3(0.0f), vec3(1.0f)}, 1.0f);
  std::mt19937 gen(11);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const vec3 axis = glm::normalize(vec3(0.3f, 0.8f, 0.2f));
  double inside = 0.0;
  for (int round = 0; round < 6; ++round) {
    const int region = guide.region(vec3(0.5f));
    inside = 0.0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
      const bool guided = region >= 0 && u(gen) < 0.5f;
      float pg = 0.0f;
      const vec3 d = guided ? guide.sample(region, {u(gen), u(gen)}, pg) : square_to_direction({u(gen), u(gen)});
      if (region >= 0 && !guided) pg = guide.pdf(region, d);
      const float pdf = region >= 0 ? 0.5f * pg + 0.5f / (4.0f * kPi) : 1.0f / (4.0f * kPi);
      const bool lit = glm::dot(d, axis) > 0.95f;
      if (guided && lit) inside += 2.0 / n;  // of the guide's own directions
      guide.record(vec3(0.5f), d, lit ? 1.0f / pdf : 0.0f);
    }
    guide.finish_round(1);
  }
  EXPECT_GT(inside, 0.5);
}

// The white furnace, guided: a white diffuse sphere under a uniform sky of 1 is 1 in
// expectation (a guided sample's weight f cos / mixture density is no longer exactly 1).
TEST(PathGuiding, WhiteFurnaceSphereIsOneGuided) {
  for (LightSampling mode : {LightSampling::Mis, LightSampling::BsdfOnly}) {
    SceneDescription scene;
    add_mesh(scene, test::make_sphere(vec3(0.0f), 1.0f, 4, add_material(scene, test::diffuse(vec3(1.0f)))));
    RenderSettings s;
    s.width = s.height = 32;
    s.spp = 256;
    s.max_bounces = 16;
    s.guiding = GuidingUse::On;
    s.light_sampling = mode;
    const RenderResult r = render(scene, test::look_at({0, 0, 2.5f}, {0, 0, 0}, 30.0f), s, vec3(1.0f));
    EXPECT_GT(r.stats.guide_rounds, 0);
    const PixelStats st = stats_of(r.image);  // the sphere fills the frame
    EXPECT_NEAR(st.mean, 1.0, 4.0 * std::sqrt(st.variance / (32 * 32)) + 1e-4) << int(mode);
  }
}

// A diffuse floor under a square emitter (test::floor_under_square_emitter), guided: MIS
// weighs light samples against the mixture's density, and the mean is the form factor's.
void expect_guided_floor_under_square_emitter(float sky, LightSampling mode) {
  SCOPED_TRACE(::testing::Message() << "sky " << sky << ", light sampling " << int(mode));
  const float a = 0.25f, h = 1.0f, le = 4.0f, albedo = 0.5f;
  SceneDescription scene;
  add_mesh(scene, test::make_quad({0, 0, 0}, {5, 0, 0}, {0, 0, -5}, add_material(scene, test::diffuse(vec3(albedo)))));
  add_mesh(scene, test::make_quad({0, h, 0}, {a, 0, 0}, {0, 0, a}, add_material(scene, test::emitter(vec3(le)))));
  RenderSettings s;
  s.width = s.height = 5;
  s.spp = 4096;
  s.max_bounces = 1;
  s.guiding = GuidingUse::On;
  s.light_sampling = mode;
  const RenderResult r = render(scene, test::look_at({0, 0.5f, 3}, {0, 0, 0}, 0.01f), s, vec3(sky));
  EXPECT_GT(r.stats.guide_rounds, 0);
  const double expected = test::floor_under_square_emitter(a, h, le, albedo) +
                          sky * (albedo - test::floor_under_square_emitter(a, h, 1.0, albedo));
  const PixelStats st = stats_of(r.image);
  EXPECT_NEAR(st.mean, expected, 4.0 * std::sqrt(st.variance + 1e-12) / std::sqrt(25.0) + 1e-4 * expected);
}

TEST(PathGuiding, FloorUnderASquareEmitterMatchesTheFormFactorGuided) {
  expect_guided_floor_under_square_emitter(1.0f, LightSampling::Mis);
  expect_guided_floor_under_square_emitter(0.0f, LightSampling::Mis);
  expect_guided_floor_under_square_emitter(0.0f, LightSampling::BsdfOnly);
}

// A caustic: a small emitter above a glass ball above a diffuse floor, a black world. The
// floor under the ball is lit only through the glass (shadow rays stop at it). The guided
// image's mean matches a render four times as long without guiding, within four standard
// errors of the two means (each from its pixels' spread).
SceneDescription caustic_scene() {
  SceneDescription scene;
  Material glass = test::diffuse(vec3(1.0f));
  glass.specular_factor = 1.0f;
  glass.transmission_factor = 1.0f;
  glass.roughness_factor = 0.0f;
  glass.thickness_factor = 1.0f;
  add_mesh(scene, test::make_quad({0, 0, 0}, {3, 0, 0}, {0, 0, -3}, add_material(scene, test::diffuse(vec3(0.8f)))));
  add_mesh(scene, test::make_sphere({0, 1, 0}, 0.5f, 4, add_material(scene, glass)));
  add_mesh(scene, test::make_quad({0, 2.2f, 0}, {0.2f, 0, 0}, {0, 0, 0.2f}, add_material(scene, test::emitter(vec3(100.0f)))));
  return scene;
}

TEST(PathGuiding, CausticUnderAGlassBallMatchesALongUnguidedRender) {
  RenderSettings s;
  s.width = s.height = 24;
  s.max_bounces = 8;
  const Camera cam = test::look_at({0, 0.6f, 1.2f}, {0, 0, 0}, 40.0f);  // the floor under the ball
  s.spp = 1024;
  s.guiding = GuidingUse::Off;
  const RenderResult unguided = render(caustic_scene(), cam, s, vec3(0.0f));
  s.spp = 256;
  s.guiding = GuidingUse::On;
  const RenderResult guided = render(caustic_scene(), cam, s, vec3(0.0f));
  EXPECT_GT(guided.stats.guide_rounds, 0);
  // Per pixel, the difference of the two is noise alone (the caustic's shape cancels): its
  // mean over the pixels, against its spread.
  const std::vector<float>& a = unguided.image.rgb;
  const std::vector<float>& b = guided.image.rgb;
  double mean_a = 0.0, sum = 0.0, squares = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    mean_a += a[i] / a.size();
    sum += b[i] - a[i];
    squares += (b[i] - a[i]) * (b[i] - a[i]);
  }
  const double n = static_cast<double>(a.size()), mean = sum / n, spread = std::sqrt(squares / n - mean * mean);
  ASSERT_GT(mean_a, 0.05);  // the caustic is there
  EXPECT_NEAR(mean, 0.0, 4.0 * spread / std::sqrt(n));
  EXPECT_LT(spread / std::sqrt(n), 0.02 * mean_a);  // sharp enough to mean something
}

// Determinism with guiding: the guide learns from whole waves, summed as integers, so the
// image is the same bits for any threads, tile size and scheduler; a crop learns from the
// whole frame's waves (traced for the guide alone), so its pixels are the whole frame's; a
// render resumed from any wave rebuilds the guide and ends with the uninterrupted film.
RenderSettings caustic_settings() {
  RenderSettings s;
  s.width = 40;
  s.height = 30;
  s.spp = 32;  // the guide learns from the waves ending at 1, 3 and 7
  s.seed = 9;
  s.guiding = GuidingUse::On;
  return s;
}

const RenderScene& caustic() {
  static const RenderScene* scene = new RenderScene(caustic_scene(), EnvironmentParams{});
  return *scene;
}

RenderResult render_caustic(const RenderSettings& s, FilmState* resume = nullptr) {
  const RenderCamera cam = caustic().camera(test::look_at({0, 1.2f, 2.5f}, {0, 0.5f, 0}, 50.0f),
                                            s.window.cropped() ? s.window.full_width : s.width,
                                            s.window.cropped() ? s.window.full_height : s.height, {});
  return render_frame(caustic(), cam, s, nullptr, resume);
}

TEST(PathGuiding, ThreadsTileSizesAndSchedulersGiveTheSameBits) {
  RenderSettings s = caustic_settings();
  s.threads = 1;
  const RenderResult one = render_caustic(s);
  EXPECT_EQ(one.stats.guide_rounds, 3);
  s.threads = 2;
  s.tile_size = 8;
  test::expect_same_image(one.image, render_caustic(s).image);
  s.tile_size = 64;
  s.scheduler = SchedulerKind::chunks;
  test::expect_same_image(one.image, render_caustic(s).image);
}

TEST(PathGuiding, ACropIsTheWholeFramesPixels) {
  RenderSettings s = caustic_settings();
  const RenderResult whole = render_caustic(s);
  RenderSettings c = s;
  c.window = {13, 7, s.width, s.height};
  c.width = 17;
  c.height = 11;
  const RenderResult crop = render_caustic(c);
  for (int y = 0; y < c.height; ++y)
    for (int x = 0; x < c.width; ++x)
      for (int k = 0; k < 3; ++k)
        ASSERT_EQ(crop.image.rgb[3 * (y * c.width + x) + k], whole.image.rgb[3 * ((y + 7) * s.width + x + 13) + k])
            << x << "," << y;
}

TEST(PathGuiding, AResumedRenderRebuildsTheGuideAndEndsWithTheSameFilm) {
  RenderSettings s = caustic_settings();
  std::vector<FilmState> checkpoints;
  s.on_checkpoint = [&](const Film& film, const RenderStats&) { checkpoints.push_back(film.state()); };
  const RenderResult whole = render_caustic(s);
  ASSERT_GE(checkpoints.size(), 4u);  // after the waves ending at 1, 3, 7, 15
  s.on_checkpoint = nullptr;
  for (std::size_t k : {std::size_t{1}, std::size_t{3}}) {  // within the learning waves, and after them
    SCOPED_TRACE(k);
    FilmState film = checkpoints[k];
    const RenderResult resumed = render_caustic(s, &film);
    test::expect_same_film(whole.film, resumed.film);
  }
}

}  // namespace
}  // namespace tessera
