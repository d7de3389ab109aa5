// --film-transparent: alpha is the camera rays' coverage, weighted by the pixel filter as the
// RGB is, and the RGB holds no background (premultiplied), while the background still lights
// the scene. A half-plane whose edge crosses a column of pixels gives each pixel's covered
// fraction in closed form. Depth is +infinity where no camera ray hit.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "renderer/camera/pixel_filter.h"
#include "renderer/render/render.h"
#include "tests/scene_builders.h"

namespace tessera {
namespace {

constexpr int kSize = 16;
constexpr float kDistance = 3.0f, kFov = 20.0f;
constexpr double kEdge = 7.3;  // the edge's image x, in pixels: column 7 is 70% covered
constexpr float kAlbedo = 0.5f, kSky = 0.8f;

// A white diffuse half-plane x >= edge facing the camera, under a uniform sky: every path
// off it reaches the sky, so each sample that hits it returns albedo * sky exactly.
RenderResult render_edge(PixelFilterKind filter, bool transparent, int spp = 256) {
  SceneDescription s;
  const float half_width = kDistance * std::tan(glm::radians(kFov) / 2.0f);  // at the plane
  const float edge_x = static_cast<float>((kEdge / (kSize / 2.0) - 1.0) * half_width);
  test::add_mesh(s, test::make_quad({edge_x + 5.0f, 0, 0}, {5, 0, 0}, {0, 5, 0},
                                    test::add_material(s, test::diffuse(vec3(kAlbedo)))));
  EnvironmentParams env;
  env.background = vec3(kSky);
  RenderScene scene(std::move(s), env);
  RenderSettings st;
  st.width = st.height = kSize;
  st.spp = spp;
  st.filter = {filter, 0.0f};
  st.aovs.coverage = transparent;
  st.aovs.depth = true;
  return render_frame(scene, make_camera(test::look_at({0, 0, kDistance}, {0, 0, 0}, kFov), kSize, kSize, {}), st);
}

// The second method: the filter's profile integrated over the covered part of its support
// (midpoint rule), for the pixel whose centre is at x + 0.5.
double covered_fraction(PixelFilterKind kind, int x) {
  const float width = default_filter_width(kind);
  const int n = 200000;
  double covered = 0.0, total = 0.0;
  for (int i = 0; i < n; ++i) {
    const double offset = (-0.5 + (i + 0.5) / n) * width;
    const double w = pixel_filter_value(kind, width, static_cast<float>(offset));
    total += w;
    if (x + 0.5 + offset > kEdge) covered += w;
  }
  return covered / total;
}

TEST(FilmTransparent, AlphaIsTheFilterWeightedCoverageOfEachPixel) {
  for (PixelFilterKind kind : {PixelFilterKind::box, PixelFilterKind::blackman_harris}) {
    const FrameImage img = render_edge(kind, true).image;
    ASSERT_EQ(img.alpha.size(), static_cast<std::size_t>(kSize * kSize));
    for (int x = 0; x < kSize; ++x) {
      const double expected = covered_fraction(kind, x);
      for (int y = 0; y < kSize; ++y)  // 256 stratified samples: within 0.02 of the fraction
        EXPECT_NEAR(img.alpha[y * kSize + x], expected, 0.02) << pixel_filter_name(kind) << " pixel " << x << "," << y;
    }
  }
}

TEST(FilmTransparent, TheRgbIsPremultipliedAndHoldsNoBackground) {
  const RenderResult transparent = render_edge(PixelFilterKind::blackman_harris, true);
  const RenderResult opaque = render_edge(PixelFilterKind::blackman_harris, false);
  EXPECT_TRUE(opaque.image.alpha.empty());  // without the option: A is 1 (image_output)
  for (int i = 0; i < kSize * kSize; ++i) {
    const float a = transparent.image.alpha[i];
    for (int c = 0; c < 3; ++c) {
      // The sky lights the plane (albedo * sky where it is seen) but is not seen itself.
      EXPECT_NEAR(transparent.image.rgb[3 * i + c], a * kAlbedo * kSky, 1e-5) << "pixel " << i;
      // The same camera rays without the option: the sky where they miss.
      EXPECT_NEAR(opaque.image.rgb[3 * i + c], a * kAlbedo * kSky + (1.0f - a) * kSky, 1e-5) << "pixel " << i;
    }
  }
}

TEST(FilmTransparent, DepthIsInfiniteWhereNothingWasHit) {
  const FrameImage img = render_edge(PixelFilterKind::box, true, 16).image;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const float depth = img.depth[y * kSize + x];
      if (x < 7) EXPECT_EQ(depth, std::numeric_limits<float>::infinity()) << x << "," << y;
      else EXPECT_NEAR(depth, kDistance, 1e-4) << x << "," << y;  // the plane, straight ahead
    }
}

}  // namespace
}  // namespace tessera
