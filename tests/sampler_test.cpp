// The samplers: pure functions of (pixel, sample, draw, seed); Sobol's stratification (every
// elementary interval of a 2D draw holds one point per 2^k samples, before and after
// scrambling); decorrelation between pixels and draws; and the convergence rates theory
// predicts for pixel integrals (independent: N^-1/2; scrambled Sobol: about N^-3/2 for a
// smooth integrand, N^-3/4 for one with an edge).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "renderer/sampling/sampler.h"

namespace tessera {
namespace {

TEST(Sampler, IsAPureFunctionOfItsKey) {
  for (SamplerKind kind : {SamplerKind::sobol, SamplerKind::independent}) {
    Sampler a(kind, 3, 5, 7, 11), b(kind, 3, 5, 7, 11);
    for (int d = 0; d < 64; ++d) ASSERT_EQ(a.next(), b.next());
    auto first = [&](std::uint32_t x, std::uint32_t y, std::uint32_t s, std::uint32_t seed) {
      return Sampler(kind, x, y, s, seed).next2();
    };
    EXPECT_NE(first(3, 5, 7, 11), first(5, 3, 7, 11));  // x and y not interchangeable
    EXPECT_NE(first(3, 5, 7, 11), first(3, 5, 8, 11));
    EXPECT_NE(first(3, 5, 7, 11), first(3, 5, 7, 12));
  }
  EXPECT_NE(Sampler(SamplerKind::sobol, 3, 5, 7, 11).next2(), Sampler(SamplerKind::independent, 3, 5, 7, 11).next2());
}

// The camera samples of a pixel draw their first 2D point together (next2_of_pixel): each
// gets what its own next2() gives, bit for bit, and its later draws are unchanged.
TEST(Sampler, APixelsSamplesDrawTogetherAsAlone) {
  for (SamplerKind kind : {SamplerKind::sobol, SamplerKind::independent})
    for (int n = 1; n <= Sampler::kTogether; ++n) {
      const std::uint64_t key = Sampler::pixel_key(kind, 17, 4, 9);
      std::vector<Sampler> together, alone;
      for (int k = 0; k < n; ++k) {
        together.emplace_back(kind, key, 40 + k);
        alone.emplace_back(kind, 17, 4, 40 + k, 9);
      }
      std::vector<Sampler*> group;
      for (Sampler& s : together) group.push_back(&s);
      std::vector<vec2> u(n);
      Sampler::next2_of_pixel(group.data(), n, u.data());
      for (int k = 0; k < n; ++k) {
        const vec2 v = alone[k].next2();
        EXPECT_EQ(std::memcmp(&u[k], &v, sizeof v), 0) << "n " << n << ", sample " << k;
        for (int d = 0; d < 5; ++d) EXPECT_EQ(together[k].next3(), alone[k].next3()) << "draw " << d + 2;
      }
    }
}

TEST(Sampler, NamesRoundTrip) {
  for (const std::string& name : sampler_names()) EXPECT_EQ(sampler_name(parse_sampler(name)), name);
  EXPECT_THROW(parse_sampler("halton"), std::invalid_argument);
}

// The generator matrices against the first Sobol points as published (Joe and Kuo's
// dimensions 1 and 2 after van der Corput, listed in Gray-code order as Antonov and Saleev
// generate them, so point i is sobol_bits(i ^ (i >> 1))): 0, (1/2,1/2,1/2), (3/4,1/4,1/4),
// (1/4,3/4,3/4), (3/8,3/8,5/8), (7/8,7/8,1/8), (5/8,1/8,7/8), (1/8,5/8,3/8).
TEST(Sobol, FirstPointsMatchTheSequence) {
  const double expected[8][3] = {{0, 0, 0},         {.5, .5, .5},       {.75, .25, .25},   {.25, .75, .75},
                                 {.375, .375, .625}, {.875, .875, .125}, {.625, .125, .875}, {.125, .625, .375}};
  for (std::uint32_t i = 0; i < 8; ++i)
    for (int d = 0; d < 3; ++d)
      EXPECT_EQ(sobol_bits(i ^ (i >> 1), d) * 0x1.0p-32, expected[i][d]) << "point " << i << " dim " << d;
}

// Every elementary interval [a/2^j, (a+1)/2^j) x [b/2^(k-j), (b+1)/2^(k-j)) holds exactly
// one of `points` (2^k of them): the (0,k,2)-net property.
void expect_net(const std::vector<vec2>& points, int k, const std::string& what) {
  for (int j = 0; j <= k; ++j) {
    std::vector<int> cells(std::size_t(1) << k, 0);
    for (const vec2& p : points) {
      const int a = static_cast<int>(p.x * float(1 << j)), b = static_cast<int>(p.y * float(1 << (k - j)));
      ++cells[(static_cast<std::size_t>(a) << (k - j)) + b];
    }
    for (std::size_t c = 0; c < cells.size(); ++c)
      ASSERT_EQ(cells[c], 1) << what << ": 2^" << k << " points, intervals 2^-" << j << " x 2^-" << k - j;
  }
}

TEST(Sobol, EveryPrefixOfEveryDrawIsANet) {
  std::vector<vec2> raw;
  for (std::uint32_t i = 0; i < (1u << 12); ++i)
    raw.push_back({bits_to_unit_float(sobol_bits(i, 0)), bits_to_unit_float(sobol_bits(i, 1))});
  for (int k = 0; k <= 12; ++k) expect_net({raw.begin(), raw.begin() + (1 << k)}, k, "unscrambled");

  // Scrambled and shuffled, for several pixels and for draws at several depths of a path;
  // both the first 2^k samples and a later aligned block of 2^k (what a resumed or adaptive
  // render adds) are nets.
  for (std::uint32_t pixel : {0u, 1u, 977u}) {
    for (int draw : {0, 1, 5, 20}) {
      std::vector<vec2> points;
      for (std::uint32_t i = 0; i < (1u << 12); ++i) {
        Sampler s(SamplerKind::sobol, pixel, 7, i, 42);
        for (int d = 0; d < draw; ++d) s.next();
        points.push_back(s.next2());
      }
      const std::string what = "pixel " + std::to_string(pixel) + " draw " + std::to_string(draw);
      for (int k = 0; k <= 12; ++k) expect_net({points.begin(), points.begin() + (1 << k)}, k, what);
      expect_net({points.begin() + 1024, points.begin() + 2048}, 10, what + ", samples 1024..2047");
    }
  }
}

// The 3D draw: its (x, y) is a net and its z is a (0,1)-sequence (one point per interval
// 2^-k in every prefix of 2^k).
TEST(Sobol, ThreeDimensionalDrawsAreStratifiedInEachProjection) {
  std::vector<vec2> xy;
  std::vector<float> z;
  for (std::uint32_t i = 0; i < 1024; ++i) {
    const vec3 u = Sampler(SamplerKind::sobol, 12, 34, i, 5).next3();
    xy.push_back({u.x, u.y});
    z.push_back(u.z);
  }
  expect_net(xy, 10, "3D draw (x, y)");
  for (int k = 0; k <= 10; ++k) {
    std::vector<int> cells(std::size_t(1) << k, 0);
    for (int i = 0; i < (1 << k); ++i) ++cells[static_cast<int>(z[i] * float(1 << k))];
    for (int c : cells) ASSERT_EQ(c, 1) << "z, 2^" << k << " points";
  }
}

// Pearson correlation of the same draw between neighbouring pixels, and between two draws
// of one pixel, over 4096 samples: uncorrelated sequences give |r| ~ N(0, 1/sqrt(4096));
// 4 standard deviations is 0.0625. An unscrambled Sobol sequence would give r = 1 between
// pixels.
TEST(Sobol, PixelsAndDrawsAreDecorrelated) {
  constexpr int kN = 4096;
  auto correlation = [](const std::vector<float>& a, const std::vector<float>& b) {
    double ma = 0, mb = 0;
    for (int i = 0; i < kN; ++i) ma += a[i], mb += b[i];
    ma /= kN, mb /= kN;
    double sab = 0, saa = 0, sbb = 0;
    for (int i = 0; i < kN; ++i) {
      sab += (a[i] - ma) * (b[i] - mb);
      saa += (a[i] - ma) * (a[i] - ma);
      sbb += (b[i] - mb) * (b[i] - mb);
    }
    return sab / std::sqrt(saa * sbb);
  };
  std::vector<float> p0, p1, second_draw;
  for (int i = 0; i < kN; ++i) {
    Sampler a(SamplerKind::sobol, 10, 10, i, 0), b(SamplerKind::sobol, 11, 10, i, 0);
    p0.push_back(a.next());
    p1.push_back(b.next());
    second_draw.push_back(a.next());
  }
  EXPECT_LT(std::fabs(correlation(p0, p1)), 0.0625);
  EXPECT_LT(std::fabs(correlation(p0, second_draw)), 0.0625);
}

// Both samplers are uniform: chi-square over 64 bins of one draw across 2^16 pixels, and of
// an 8x8 grid of a 2D draw. With 63 degrees of freedom the 99.9th percentile is 103.4.
TEST(Sampler, IsUniformAcrossPixels) {
  constexpr int kBins = 64, kN = 1 << 16;
  auto chi2 = [&](const std::vector<int>& counts) {
    const double expected = static_cast<double>(kN) / kBins;
    double c = 0;
    for (int n : counts) c += (n - expected) * (n - expected) / expected;
    return c;
  };
  for (SamplerKind kind : {SamplerKind::sobol, SamplerKind::independent}) {
    for (std::uint32_t sample : {0u, 3u, 1000u}) {
      std::vector<int> bins(kBins, 0), grid(kBins, 0);
      for (int i = 0; i < kN; ++i) {
        Sampler s(kind, i % 256, i / 256, sample, 99);
        const float u = s.next();
        const vec2 v = s.next2();
        ASSERT_GE(u, 0.0f);
        ASSERT_LT(u, 1.0f);
        ++bins[static_cast<int>(u * kBins)];
        ++grid[static_cast<int>(v.x * 8) * 8 + static_cast<int>(v.y * 8)];
      }
      EXPECT_LT(chi2(bins), 103.4) << sampler_name(kind) << " sample " << sample;
      EXPECT_LT(chi2(grid), 103.4) << sampler_name(kind) << " sample " << sample;
    }
  }
}

// Root-mean-square error of the N-sample estimate of a pixel integral, over 256 pixels
// (independent scramblings), for N = 16 ... 4096; returns the slope of log(RMSE) against
// log(N) by least squares.
template <typename F>
double convergence_slope(SamplerKind kind, F f, double exact) {
  std::vector<double> log_n, log_e;
  for (int n = 16; n <= 4096; n *= 4) {
    double sq = 0;
    for (int pixel = 0; pixel < 256; ++pixel) {
      double sum = 0;
      for (int i = 0; i < n; ++i) {
        Sampler s(kind, pixel, 0, i, 1);
        s.next();  // a later draw, as a bounce's is
        sum += f(s.next2());
      }
      sq += (sum / n - exact) * (sum / n - exact);
    }
    log_n.push_back(std::log(double(n)));
    log_e.push_back(0.5 * std::log(sq / 256));
  }
  const double k = static_cast<double>(log_n.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < log_n.size(); ++i) {
    sx += log_n[i], sy += log_e[i], sxx += log_n[i] * log_n[i], sxy += log_n[i] * log_e[i];
  }
  return (k * sxy - sx * sy) / (k * sxx - sx * sx);
}

TEST(Sampler, SobolConvergesFasterThanIndependentOnPixelIntegrals) {
  // Smooth: a Gaussian bump, its integral over the unit square from erf.
  const double sigma = 0.3, exact_1d = sigma * std::sqrt(kPi / 2) * std::erf(0.5 / (sigma * std::sqrt(2.0))) * 2;
  auto smooth = [&](vec2 u) {
    return std::exp(-((u.x - 0.5) * (u.x - 0.5) + (u.y - 0.5) * (u.y - 0.5)) / (2 * sigma * sigma));
  };
  // An edge through the pixel: the half-plane below x + 0.7 y = 0.8 (a non-axis-aligned
  // silhouette), area by geometry: the region x < 0.8 - 0.7 y for y in [0, 1] is a trapezoid
  // with widths 0.8 and 0.1, area 0.45.
  auto edge = [](vec2 u) { return u.x + 0.7 * u.y < 0.8 ? 1.0 : 0.0; };
  const double smooth_exact = exact_1d * exact_1d, edge_exact = 0.45;

  const double independent_smooth = convergence_slope(SamplerKind::independent, smooth, smooth_exact);
  const double independent_edge = convergence_slope(SamplerKind::independent, edge, edge_exact);
  const double sobol_smooth = convergence_slope(SamplerKind::sobol, smooth, smooth_exact);
  const double sobol_edge = convergence_slope(SamplerKind::sobol, edge, edge_exact);
  // Monte Carlo: -1/2. Scrambled nets: -3/2 for smooth integrands (Owen 1997), -3/4 for a
  // discontinuity along a line (its variance is O(N^-3/2)).
  EXPECT_NEAR(independent_smooth, -0.5, 0.1);
  EXPECT_NEAR(independent_edge, -0.5, 0.1);
  EXPECT_LT(sobol_smooth, -1.3);
  EXPECT_LT(sobol_edge, -0.68);
  EXPECT_GT(sobol_edge, -1.0);  // not better than theory allows: the estimate is honest
}

}  // namespace
}  // namespace tessera
