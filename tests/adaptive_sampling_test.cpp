// The half buffers (means of the even- and odd-numbered samples) and adaptive sampling:
// the halves add up to the beauty and equal the closed form on a constant image; Cycles'
// estimator and its neighbourhood on hand-made films; a whole adaptive render stops its
// flat pixels at the minimum, keeps sampling the noisy ones, stays within a few standard
// errors of a non-adaptive reference, and gives the same bits for any threads, tiles and
// after a resume.
#include <gtest/gtest.h>

#include <cmath>

#include "renderer/sampling/adaptive_sampling.h"
#include "imageio/image_output.h"
#include "renderer/render/render.h"
#include "imageio/resume_layers.h"
#include "tests/scene_builders.h"
#include "tests/same_bits.h"
#include "tests/test_support.h"

namespace tessera {
namespace {

constexpr float kBackground = 0.2f;

// Top: nothing but the uniform background (every sample the same: flat). Below: a diffuse
// floor and sphere under a small emitter, with a soft shadow and indirect light (noisy).
const RenderScene& scene() {
  static const RenderScene* s = [] {
    SceneDescription d = test::lit_floor_and_sphere();
    EnvironmentParams env;
    env.background = vec3(kBackground);
    return new RenderScene(std::move(d), env);
  }();
  return *s;
}

RenderSettings adaptive_settings() {
  RenderSettings s;
  s.width = 40;
  s.height = 30;
  s.spp = 256;
  s.max_bounces = 4;
  s.seed = 5;
  s.tile_size = 8;
  s.aovs.halves = true;
  s.adaptive = {0.004f, 16};
  return s;
}

const RenderCamera& camera() {
  static const RenderCamera cam = make_camera(test::look_at({0, 0, 4}, {0, -0.5f, 0}, 40.0f), 40, 30, {});
  return cam;
}

using test::expect_same_film;
using test::same_bits;

// The render the other tests compare with: threads and tiles vary, the bits must not.
const RenderResult& adaptive_render() {
  static const RenderResult r = render_frame(scene(), camera(), adaptive_settings());
  return r;
}

// --- the halves -----------------------------------------------------------------------

// Each resolved mean is a double rounded to float (relative error 2^-24), so the
// count-weighted halves and the beauty agree within 2^-23 of their magnitudes.
void expect_halves_combine(const std::vector<float>& all, const std::vector<float>& even,
                           const std::vector<float>& odd, const std::vector<std::uint32_t>& counts) {
  ASSERT_EQ(all.size(), even.size());
  ASSERT_EQ(all.size(), odd.size());
  for (std::size_t i = 0; i < all.size(); ++i) {
    const double n = counts[i / 3], n_odd = counts[i / 3] / 2, n_even = n - n_odd;
    const double combined = (n_even * even[i] + n_odd * odd[i]) / n;
    const double bound = std::ldexp((n_even * std::abs(even[i]) + n_odd * std::abs(odd[i])) / n + std::abs(all[i]), -23);
    ASSERT_NEAR(combined, all[i], bound + 1e-30) << "value " << i;
  }
}

TEST(FilmHalves, EvenAndOddCombineToTheBeauty) {
  RenderSettings s = adaptive_settings();
  s.adaptive = {};
  s.spp = 20;  // waves end at 1, 3, 7, 15, 20: odd and even counts
  s.aovs = {true, true, false, true};
  const FrameImage img = render_frame(scene(), camera(), s).image;
  ASSERT_EQ(img.pixel_samples, std::vector<std::uint32_t>(40 * 30, 20));
  expect_halves_combine(img.rgb, img.rgb_even, img.rgb_odd, img.pixel_samples);
  expect_halves_combine(img.albedo, img.albedo_even, img.albedo_odd, img.pixel_samples);
  expect_halves_combine(img.normal, img.normal_even, img.normal_odd, img.pixel_samples);
  EXPECT_FALSE(same_bits(img.rgb_even, img.rgb_odd));  // a noisy scene: the halves are different estimates
}

// With 2 samples the even half is sample 0 alone: what a 1-sample render gives, exactly
// (the double sum s0 + s1 - s1 is s0 for floats of similar size).
TEST(FilmHalves, TheEvenHalfOfTwoSamplesIsTheFirstSample) {
  RenderSettings s = adaptive_settings();
  s.adaptive = {};
  s.spp = 1;
  const FrameImage one = render_frame(scene(), camera(), s).image;
  s.spp = 2;
  const FrameImage two = render_frame(scene(), camera(), s).image;
  EXPECT_TRUE(same_bits(one.rgb, two.rgb_even));
  EXPECT_TRUE(same_bits(one.rgb_odd, std::vector<float>(one.rgb.size(), 0.0f)));  // one sample: no odd one
  EXPECT_FALSE(same_bits(two.rgb_even, two.rgb_odd));
}

// An emitter filling the view head-on: every sample is its radiance (1, 2, 3), so both
// halves are too, and its normal faces the camera (+Z).
TEST(FilmHalves, OnAConstantImageBothHalvesAreTheClosedForm) {
  SceneDescription d;
  Material m = test::emitter(vec3(0.25f, 0.5f, 0.75f));
  m.emissive_strength = 4.0f;
  test::add_mesh(d, test::make_quad({0, 0, 0}, {10, 0, 0}, {0, 10, 0}, test::add_material(d, m)));
  const RenderScene quad(std::move(d), EnvironmentParams{});
  RenderSettings s;
  s.width = s.height = 16;
  s.spp = 7;
  s.aovs = {false, true, false, true};
  const FrameImage img = render_frame(quad, make_camera(test::look_at({0, 0, 3}, {0, 0, 0}, 30.0f), 16, 16, {}), s).image;
  for (std::size_t i = 0; i < img.rgb.size(); i += 3) {
    for (const std::vector<float>* half : {&img.rgb_even, &img.rgb_odd}) {
      ASSERT_FLOAT_EQ((*half)[i + 0], 1.0f);
      ASSERT_FLOAT_EQ((*half)[i + 1], 2.0f);
      ASSERT_FLOAT_EQ((*half)[i + 2], 3.0f);
    }
    for (const std::vector<float>* half : {&img.normal_even, &img.normal_odd})
      ASSERT_NEAR((*half)[i + 2], 1.0f, 1e-6f);
  }
  EXPECT_EQ(img.pixel_samples, std::vector<std::uint32_t>(16 * 16, 7));
  ASSERT_EQ(img.rgb_variance.size(), img.rgb.size());
  for (float v : img.rgb_variance) ASSERT_EQ(v, 0.0f);  // every sample the same
}

// Each pixel's variance of its mean, s^2 / n, from sums the tiles add wave by wave: samples
// 1, 2, 3, 4, 10 (mean 4, s^2 = (9 + 4 + 1 + 0 + 36) / 4 = 12.5, over 5: 2.5) in R, their
// doubles in G, none varying in B; a pixel of one sample has none (0).
TEST(FilmHalves, EachPixelsVarianceIsItsSamplesOverTheirCount) {
  Film film(2, 1, AovSelection{false, false, false, true});
  const double values[] = {1, 2, 3, 4, 10};
  PixelSums first, second;
  for (int s = 0; s < 5; ++s) {
    PixelSums& p = s < 2 ? first : second;
    const glm::dvec3 x(values[s], 2 * values[s], 7.0);
    ++p.samples, p.radiance += x, p.radiance_sq += x * x;
    if (s % 2 == 1) p.radiance_odd += x;
  }
  film.add(0, 0, first);
  film.add(0, 0, second);
  PixelSums one;
  one.samples = 1, one.radiance = one.radiance_sq = glm::dvec3(3.0);
  film.add(1, 0, one);
  const FrameImage img = film.resolve();
  ASSERT_EQ(img.rgb_variance.size(), 6u);
  EXPECT_FLOAT_EQ(img.rgb_variance[0], 2.5f);
  EXPECT_FLOAT_EQ(img.rgb_variance[1], 10.0f);
  EXPECT_EQ(img.rgb_variance[2], 0.0f);
  for (int c = 3; c < 6; ++c) EXPECT_EQ(img.rgb_variance[c], 0.0f);
  EXPECT_TRUE(Film(2, 1, AovSelection{}).resolve().rgb_variance.empty());  // only with the halves
}

// --- the estimator, on hand-made numbers ------------------------------------------------

TEST(AdaptiveEstimator, IsCyclesErrorOverTheSquareRootOfDarkIntensity) {
  // |0.25-0.3| + |0.25-0.2| + 0 = 0.1 over 0.0001 + sqrt(0.75)
  EXPECT_NEAR(pixel_error({0.25, 0.25, 0.25}, {0.3, 0.2, 0.25}, 8), 0.1 / (0.0001 + 0.8660254037844386), 1e-12);
  // bright: R+G+B = 3 >= 1 normalises by the intensity itself: 0.3 / 3.0001
  EXPECT_NEAR(pixel_error({1.0, 1.0, 1.0}, {1.1, 0.9, 1.1}, 8), 0.3 / 3.0001, 1e-12);
  EXPECT_TRUE(std::isinf(pixel_error({1, 1, 1}, {1, 1, 1}, 1)));  // one sample has no odd half
}

TEST(AdaptiveEstimator, AutomaticMinimumIsCycles) {
  // Cycles' own figures: threshold 0.1 -> 32, 0.01 -> 64, 0.001 -> 128; never below 4 or above spp.
  EXPECT_EQ(adaptive_min_spp({0.1f, 0}, 4096), 32);
  EXPECT_EQ(adaptive_min_spp({0.01f, 0}, 4096), 64);
  EXPECT_EQ(adaptive_min_spp({0.001f, 0}, 4096), 128);
  EXPECT_EQ(adaptive_min_spp({0.01f, 0}, 40), 40);
  EXPECT_EQ(adaptive_min_spp({0.01f, 2}, 4096), 4);
  EXPECT_EQ(adaptive_min_spp({0.01f, 100}, 4096), 100);
}

TEST(AdaptiveEstimator, WavesGainABoundaryAtTheMinimum) {
  std::vector<int> ends;
  for (const SampleWave& w : make_adaptive_waves(100, 16)) ends.push_back(w.end);
  EXPECT_EQ(ends, (std::vector<int>{1, 3, 7, 15, 16, 31, 63, 100}));
  ends.clear();
  for (const SampleWave& w : make_adaptive_waves(20, 15)) ends.push_back(w.end);  // already a wave end
  EXPECT_EQ(ends, (std::vector<int>{1, 3, 7, 15, 20}));
}

// A 5x5 film, every pixel's halves equal (error 0) but one whose odd half is far off: that
// pixel and its 3x3 neighbourhood (clipped at the border) go on, the rest converge.
FilmState film_with_noisy_pixel(int nx, int ny) {
  FilmState f = FilmState::empty(5, 5, {}, true);
  for (std::size_t i = 0; i < f.pixel_count(); ++i) {
    f.samples[i] = 16;
    f.radiance[i] = glm::dvec3(16 * 0.5);
    f.radiance_odd[i] = glm::dvec3(8 * 0.5);
  }
  f.radiance_odd[static_cast<std::size_t>(ny) * 5 + nx] = glm::dvec3(8 * 0.9);
  return f;
}

TEST(AdaptiveEstimator, ANoisyPixelKeepsItsNeighboursGoing) {
  FilmState f = film_with_noisy_pixel(2, 2);
  EXPECT_EQ(check_convergence(f, {0.01f, 16, 16}), 25u - 9u);
  EXPECT_EQ(f.converged[2 * 5 + 1], 0);
  EXPECT_EQ(f.converged[0], 1);
  EXPECT_EQ(f.checked_at, 16u);
  FilmState corner = film_with_noisy_pixel(0, 0);
  EXPECT_EQ(check_convergence(corner, {0.01f, 16, 16}), 25u - 4u);
  FilmState early = film_with_noisy_pixel(0, 0);
  EXPECT_EQ(check_convergence(early, {0.01f, 17, 16}), 0u);  // below the minimum nothing stops
}

// --- whole adaptive renders ---------------------------------------------------------------

// Pixels whose every sample of a `same seed` render saw only the background: with the same
// seed the adaptive render's first samples are among them, so its halves agree exactly.
std::vector<bool> pure_background(const FrameImage& img) {
  std::vector<bool> pure(img.rgb.size() / 3);
  for (std::size_t i = 0; i < pure.size(); ++i) {
    bool p = true;
    for (int c = 0; c < 3; ++c)
      p = p && img.rgb[3 * i + c] == kBackground && img.rgb_even[3 * i + c] == kBackground &&
          img.rgb_odd[3 * i + c] == kBackground;
    pure[i] = p;
  }
  return pure;
}

bool neighbourhood_pure(const std::vector<bool>& pure, int x, int y, int w, int h) {
  for (int yy = std::max(0, y - 1); yy <= std::min(h - 1, y + 1); ++yy)
    for (int xx = std::max(0, x - 1); xx <= std::min(w - 1, x + 1); ++xx)
      if (!pure[static_cast<std::size_t>(yy) * w + xx]) return false;
  return true;
}

// Per pixel, the variance of one sample of R+G+B from the halves: E[(even - odd)^2] =
// sigma^2 (1/n_even + 1/n_odd). One degree of freedom per pixel, but summed over a region
// a sound estimate of the region mean's variance.
double sample_variance(const FrameImage& img, std::size_t i) {
  double d = 0.0;
  for (int c = 0; c < 3; ++c) d += img.rgb_even[3 * i + c] - img.rgb_odd[3 * i + c];
  const double n = img.pixel_samples[i], n_odd = std::floor(n / 2), n_even = n - n_odd;
  return d * d / (1.0 / n_even + 1.0 / n_odd);
}

// Per pixel, the standard deviation of one sample's R+G+B and its mean, from 8 renders of
// 64 spp with other seeds than the adaptive one: 7 degrees of freedom each.
struct PixelNoise {
  std::vector<double> sigma, mean;
};

PixelNoise pixel_noise() {
  constexpr int kRenders = 8, kSpp = 64;
  RenderSettings s = adaptive_settings();
  s.adaptive = {};
  s.spp = kSpp;
  s.sampler = SamplerKind::independent;  // sigma: the standard deviation of one independent sample
  std::vector<std::vector<double>> m(kRenders);
  for (int k = 0; k < kRenders; ++k) {
    s.seed = 1000 + k;
    const FrameImage img = render_frame(scene(), camera(), s).image;
    for (std::size_t i = 0; i < img.rgb.size() / 3; ++i) m[k].push_back(img.rgb[3 * i] + img.rgb[3 * i + 1] + img.rgb[3 * i + 2]);
  }
  PixelNoise noise;
  for (std::size_t i = 0; i < m[0].size(); ++i) {
    double mean = 0.0, var = 0.0;
    for (int k = 0; k < kRenders; ++k) mean += m[k][i] / kRenders;
    for (int k = 0; k < kRenders; ++k) var += (m[k][i] - mean) * (m[k][i] - mean) / (kRenders - 1);
    noise.mean.push_back(mean);
    noise.sigma.push_back(std::sqrt(var * kSpp));
  }
  return noise;
}

// Flat pixels, and their neighbours, stop at exactly the minimum. A pixel stops at 16
// samples only if |I - A| over its normaliser is below 5T; for the sum of the channels
// I - A has standard deviation sigma/4 at 16 samples (8 odd of 16: (1/2) sigma sqrt(1/8 +
// 1/8)), and the error sums absolute values, so it is at least that. Where sigma/4 is ten
// times 5T x normaliser, |I - A| falls below it with probability about 0.8/10: such a
// pixel must mostly go on. A lower threshold than the other tests' makes many such pixels.
TEST(AdaptiveRender, FlatPixelsStopAtTheMinimumNoisyOnesGoOn) {
  RenderSettings low = adaptive_settings();
  low.adaptive.threshold = 0.0005f;
  low.sampler = SamplerKind::independent;  // the bounds below are for independent samples
  const RenderResult r = render_frame(scene(), camera(), low);
  RenderSettings ref = low;
  ref.adaptive = {};
  ref.spp = 1024;  // the same seed and sampler: a superset of the adaptive render's samples
  const std::vector<bool> pure = pure_background(render_frame(scene(), camera(), ref).image);
  const PixelNoise noise = pixel_noise();
  const double limit = 5.0 * low.adaptive.threshold;
  int flat = 0, noisy = 0, noisy_at_min = 0, stopped_early = 0;
  for (int y = 0; y < 30; ++y) {
    for (int x = 0; x < 40; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * 40 + x;
      const std::uint32_t n = r.film.samples[i];
      if (neighbourhood_pure(pure, x, y, 40, 30)) {
        ++flat;
        EXPECT_EQ(n, 16u) << x << "," << y;
        EXPECT_EQ(r.film.converged[i], 1);
        continue;
      }
      const double s = noise.mean[i], normaliser = 0.0001 + (s < 1.0 ? std::sqrt(s) : s);
      if (noise.sigma[i] / 4.0 > 10.0 * limit * normaliser) {
        ++noisy;
        noisy_at_min += n == 16;
      }
      const std::uint32_t n_default = adaptive_render().film.samples[i];
      stopped_early += !pure[i] && n_default > 16 && n_default < 256;
    }
  }
  EXPECT_GT(flat, 300);  // the sky
  EXPECT_GT(noisy, 40);  // on the floor and the sphere
  EXPECT_LE(noisy_at_min, noisy * 2 / 10);  // about 8% expected at most
  EXPECT_GT(stopped_early, 100);  // the default threshold stops many lit pixels between 16 and spp
  EXPECT_EQ(r.stats.converged_pixels, static_cast<std::uint64_t>(std::count(r.film.converged.begin(), r.film.converged.end(), 1)));
  EXPECT_EQ(r.image.samples_per_pixel, 16);
  EXPECT_FALSE(r.stats.time_limited);
}

// Stopping a pixel when its halves agree could favour some outcomes; the mean over the noisy
// pixels must stay within 4 standard errors of an independent reference (another seed,
// 1024 spp everywhere), the errors of both taken from the reference's per-pixel variance.
TEST(AdaptiveRender, TheNoisyRegionMeanIsWithinItsStandardErrorOfTheReference) {
  RenderSettings independent = adaptive_settings();
  independent.sampler = SamplerKind::independent;  // standard errors from the sample variance hold for it
  const RenderResult r = render_frame(scene(), camera(), independent);
  RenderSettings ref_settings = independent;
  ref_settings.adaptive = {};
  ref_settings.spp = 1024;
  ref_settings.seed = 77;
  const FrameImage ref = render_frame(scene(), camera(), ref_settings).image;
  double adaptive_mean = 0.0, ref_mean = 0.0, var_adaptive = 0.0, var_ref = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < ref.pixel_samples.size(); ++i) {
    if (r.film.samples[i] == 16) continue;  // the flat pixels: exact in both
    const double sigma2 = sample_variance(ref, i);
    adaptive_mean += r.image.rgb[3 * i] + r.image.rgb[3 * i + 1] + r.image.rgb[3 * i + 2];
    ref_mean += ref.rgb[3 * i] + ref.rgb[3 * i + 1] + ref.rgb[3 * i + 2];
    var_adaptive += sigma2 / r.film.samples[i];
    var_ref += sigma2 / 1024.0;
    ++n;
  }
  ASSERT_GT(n, 300);
  const double se = std::sqrt(var_adaptive + var_ref) / n;
  EXPECT_NEAR(adaptive_mean / n, ref_mean / n, 4.0 * se) << "standard error " << se;
  EXPECT_GT(se, 0.0);
}

TEST(AdaptiveRender, OneOrTwoThreadsAndAnyTileSizeGiveTheSameBits) {
  RenderSettings s = adaptive_settings();
  s.threads = 1;
  s.tile_size = 5;
  expect_same_film(adaptive_render().film, render_frame(scene(), camera(), s).film);
  s.threads = 2;
  s.tile_size = 16;
  s.scheduler = SchedulerKind::chunks;
  expect_same_film(adaptive_render().film, render_frame(scene(), camera(), s).film);
}

// The film after each wave but the last, as checkpoints see it.
std::vector<FilmState> checkpoints() {
  std::vector<FilmState> states;
  RenderSettings s = adaptive_settings();
  s.on_checkpoint = [&](const Film& film, const RenderStats&) { states.push_back(film.state()); };
  render_frame(scene(), camera(), s);
  return states;
}

TEST(AdaptiveResume, FromEveryCheckpointGivesTheSameBits) {
  std::vector<FilmState> states = checkpoints();
  ASSERT_GE(states.size(), 6u);  // waves end at 1, 3, 7, 15, 16, 31, ...
  RenderSettings s = adaptive_settings();
  s.threads = 1;
  s.tile_size = 13;
  for (FilmState& state : states) {
    const std::uint32_t at = state.checked_at;
    SCOPED_TRACE(at);
    const RenderResult resumed = render_frame(scene(), camera(), s, nullptr, &state);
    expect_same_film(adaptive_render().film, resumed.film);
    EXPECT_TRUE(same_bits(adaptive_render().image.rgb, resumed.image.rgb));
  }
}

// Stopped in the middle of a wave: the top rows finished it, the rest did not, and the
// flags are still those of the check before it. The resumed render finishes that wave,
// then checks, as the uninterrupted one did.
TEST(AdaptiveResume, FromAWaveStoppedHalfwayGivesTheSameBits) {
  const std::vector<FilmState> states = checkpoints();
  for (std::size_t k = 4; k + 1 < states.size(); ++k) {
    SCOPED_TRACE(k);
    FilmState mixed = states[k];
    const FilmState& next = states[k + 1];
    for (std::size_t i = 0; i < mixed.pixel_count() / 2; ++i) {
      mixed.radiance[i] = next.radiance[i];
      mixed.radiance_odd[i] = next.radiance_odd[i];
      mixed.samples[i] = next.samples[i];
    }
    const RenderResult resumed = render_frame(scene(), camera(), adaptive_settings(), nullptr, &mixed);
    expect_same_film(adaptive_render().film, resumed.film);
  }
}

TEST(AdaptiveResume, TheExrCarriesOddSumsAndFlagsLosslessly) {
  RenderSettings s = adaptive_settings();
  s.aovs = {true, true, false, true};
  FilmState film;
  s.on_checkpoint = [&](const Film& f, const RenderStats&) { if (f.state().checked_at == 63) film = f.state(); };
  render_frame(scene(), camera(), s);
  ASSERT_EQ(film.checked_at, 63u);
  ASSERT_GT(Film(film).converged_pixels(), 0u);
  const std::string path = test::make_temp_dir("adaptive-resume-exr") + "/frame.exr";
  ImageWriteParams params;
  params.metadata.partial = true;
  params.resume_film = &film;
  params.resume_settings = "format=1\n";
  write_image(path, Film(film).resolve(), params);
  const FilmState back = read_resume_film(path, {40, 30, s.aovs, 256, 16});
  expect_same_film(back, film);
  EXPECT_TRUE(same_bits(back.albedo, film.albedo));
  EXPECT_TRUE(same_bits(back.normal, film.normal));
}

TEST(AdaptiveResume, ATimeLimitedRenderResumesToTheSameBits) {
  RenderSettings s = adaptive_settings();
  s.time_limit = 1e-9;  // stops after the first wave
  RenderResult part = render_frame(scene(), camera(), s);
  EXPECT_TRUE(part.stats.time_limited);
  EXPECT_EQ(part.image.samples_per_pixel, 1);
  const RenderResult resumed = render_frame(scene(), camera(), adaptive_settings(), nullptr, &part.film);
  expect_same_film(adaptive_render().film, resumed.film);
}

}  // namespace
}  // namespace tessera
