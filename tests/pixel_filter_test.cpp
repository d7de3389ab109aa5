// The pixel filter's importance sampling against the filter itself: the offsets it draws
// follow the normalised profile (chi-square against a quadrature of the profile), and a
// rendered edge shows the profile's integral across it, as filtering the image would.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "renderer/camera/pixel_filter.h"
#include "renderer/render/render.h"
#include "tests/chi_square.h"
#include "tests/scene_builders.h"

namespace tessera {
namespace {

// The profile's share on [a, b] (pixels from the centre): midpoint rule on 20000 points.
double profile_share(PixelFilterKind kind, float width, double a, double b) {
  auto integral = [&](double lo, double hi) {
    const int n = 20000;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) sum += pixel_filter_value(kind, width, static_cast<float>(lo + (i + 0.5) * (hi - lo) / n));
    return sum * (hi - lo) / n;
  };
  return integral(a, b) / integral(-0.5 * width, 0.5 * width);
}

class PixelFilterSampling : public ::testing::TestWithParam<std::pair<PixelFilterKind, float>> {};

TEST_P(PixelFilterSampling, OffsetsFollowTheProfile) {
  const auto [kind, width] = GetParam();
  const PixelFilter filter({kind, width});
  const int bins = 40, n = 200000;
  std::vector<double> observed(bins, 0.0);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  for (int i = 0; i < n; ++i) {
    const vec2 at = filter.sample({uniform(rng), uniform(rng)});
    for (float v : {at.x, at.y}) {
      const double x = v - 0.5;  // from the pixel centre
      ASSERT_LE(std::fabs(x), 0.5 * width + 1e-5);
      ++observed[std::min(bins - 1, static_cast<int>((x / width + 0.5) * bins))];
    }
  }
  double chi2 = 0.0;
  int dof = -1;
  for (int b = 0; b < bins; ++b) {
    const double expected =
        2.0 * n * profile_share(kind, width, width * (double(b) / bins - 0.5), width * (double(b + 1) / bins - 0.5));
    if (expected < 5.0) continue;  // the far tails: too few to test
    chi2 += std::pow(observed[b] - expected, 2) / expected;
    ++dof;
  }
  const double p = test::gamma_q(0.5 * dof, 0.5 * chi2);
  EXPECT_GT(p, 1e-4) << pixel_filter_name(kind) << " " << width << ": chi2 " << chi2 << " over " << dof << " dof";
}

INSTANTIATE_TEST_SUITE_P(Filters, PixelFilterSampling,
                         ::testing::Values(std::pair{PixelFilterKind::blackman_harris, 1.5f},
                                           std::pair{PixelFilterKind::blackman_harris, 4.0f},
                                           std::pair{PixelFilterKind::gaussian, 1.5f},
                                           std::pair{PixelFilterKind::box, 2.0f}));

// The box of width 1 is the pixel's own square: the raw jitter, bit for bit (images made
// before filters existed are reproduced exactly with --pixel-filter box).
TEST(PixelFilter, UnitBoxKeepsTheJitter) {
  const PixelFilter box({PixelFilterKind::box, 0.0f});
  for (float u : {0.0f, 0.25f, 0.5f, 0.99999994f}) EXPECT_EQ(box.sample({u, 1.0f - u}), vec2(u, 1.0f - u));
}

// An emitter of radiance 1 covering the left half of the view head-on, black beyond: each
// pixel near the edge shows the filter's share on the emitter's side of it, i.e. the
// profile's integral from -width/2 to the edge's distance from the pixel centre.
TEST(PixelFilter, RenderedEdgeIsTheProfileIntegral) {
  for (const PixelFilterParams filter : {PixelFilterParams{PixelFilterKind::blackman_harris, 0.0f},
                                         PixelFilterParams{PixelFilterKind::gaussian, 3.0f}}) {
    SceneDescription scene;
    // Pinhole at z = 3 with a 30 degree view of 16 pixels: the plane z = 0 spans
    // 2 * 3 tan(15 deg) units, the edge x = 0 runs between pixels 7 and 8.
    test::add_mesh(scene, test::make_quad({-10, 0, 0}, {10, 0, 0}, {0, 10, 0},
                                          test::add_material(scene, test::emitter(vec3(1.0f)))));
    RenderSettings s;
    s.width = s.height = 16;
    s.spp = 1024;
    s.filter = filter;
    EnvironmentParams env;
    env.background = vec3(0.0f);
    RenderScene rs(std::move(scene), env);
    const RenderResult r = render_frame(rs, make_camera(test::look_at({0, 0, 3}, {0, 0, 0}, 30.0f), 16, 16, {}), s);
    const float width = filter_width(filter);
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 16; ++x) {
        const double edge = 8.0 - (x + 0.5);  // the edge's offset from this pixel's centre
        const double expected = profile_share(filter.kind, width, -0.5 * width, std::clamp(edge, -0.5 * width, 0.5 * width));
        const double sigma = std::sqrt(expected * (1.0 - expected) / s.spp);  // independent samples' error
        ASSERT_NEAR(r.image.rgb[3 * (y * 16 + x)], expected, 4.0 * sigma + 1e-4)
            << describe(filter) << " pixel " << x << "," << y;
      }
  }
}

}  // namespace
}  // namespace tessera
