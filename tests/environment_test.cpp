// The environment map's direction mapping, against Blender's equirectangular formula after
// Blender's glTF axis conversion (x_b = x, y_b = -z, z_b = y): the same image must light a
// scene the same way in both renderers.
#include <gtest/gtest.h>

#include <cmath>

#include <OpenImageIO/imageio.h>

#include "renderer/lights/environment.h"
#include "renderer/render/render.h"
#include "renderer/sampling/sampler.h"
#include "tests/chi_square.h"
#include "tests/scene_builders.h"
#include "tests/test_support.h"
#include "imageio/environment_image.h"

namespace tessera {
namespace {

vec2 blender_uv(const vec3& d) {  // Cycles' direction_to_equirectangular, v from the top row
  const double xb = d.x, yb = -d.z, zb = d.y;
  const double u = 0.5 - std::atan2(yb, xb) / (2 * M_PI);
  const double v_up = 0.5 + std::atan2(zb, std::hypot(xb, yb)) / M_PI;
  return vec2(static_cast<float>(u), static_cast<float>(1.0 - v_up));
}

TEST(Environment, MappingMatchesBlender) {
  const Environment env(EnvironmentParams{});
  for (int i = 0; i < 1000; ++i) {
    Sampler rng(SamplerKind::independent, i, 0, 0, 3);
    const float z = 2 * rng.next() - 1, phi = 2 * kPi * rng.next(), r = std::sqrt(1 - z * z);
    const vec3 d(r * std::cos(phi), z, r * std::sin(phi));
    const vec2 ours = env.direction_to_uv(d), theirs = blender_uv(d);
    const float du = std::fabs(ours.x - theirs.x);
    EXPECT_LT(std::fmin(du, 1.0f - du), 1e-5f) << d.x << " " << d.y << " " << d.z;  // u wraps around
    EXPECT_NEAR(ours.y, theirs.y, 1e-5f);
  }
  EXPECT_NEAR(env.direction_to_uv({1, 0, 0}).x, 0.5f, 1e-6f);  // the image centre faces +X
  EXPECT_NEAR(env.direction_to_uv({0, 1, 0}).y, 0.0f, 1e-6f);  // the top row is straight up
}

TEST(Environment, RotationTurnsTheMapAboutY) {
  EnvironmentParams p;
  p.rotate_degrees = 90.0f;
  const Environment rotated(p), plain(EnvironmentParams{});
  // Turning the map by +90 degrees about +Y moves what was at +X to -Z (right-handed).
  const vec2 a = plain.direction_to_uv({1, 0, 0}), b = rotated.direction_to_uv({0, 0, -1});
  EXPECT_NEAR(a.x, b.x, 1e-5f);
  EXPECT_NEAR(a.y, b.y, 1e-5f);
}

}  // namespace
}  // namespace tessera

namespace tessera {
namespace {

// A small HDR environment with a bright sun-like spot on a gradient sky, written to disk.
std::string write_test_environment(const std::string& name) {
  const int w = 64, h = 32;
  std::vector<float> pixels(3 * w * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float sky = 0.2f + 0.8f * (1.0f - float(y) / h);
      const bool sun = std::abs(x - 40) <= 1 && std::abs(y - 9) <= 1;
      for (int c = 0; c < 3; ++c) pixels[3 * (y * w + x) + c] = sun ? 200.0f : sky * (c + 1) / 3.0f;
    }
  const std::string path = test::make_temp_dir(name) + "/sky.exr";
  auto out = OIIO::ImageOutput::create(path);
  out->open(path, OIIO::ImageSpec(w, h, 3, OIIO::TypeDesc::FLOAT));
  out->write_image(OIIO::TypeDesc::FLOAT, pixels.data());
  out->close();
  return path;
}

TEST(Environment, ImportanceSamplingMatchesItsPdfChiSquare) {
  for (float rotate : {0.0f, 70.0f}) {
    EnvironmentParams p;
    p.image_path = write_test_environment("env-chi2");
    p.image = read_environment_image(p.image_path);
    p.rotate_degrees = rotate;
    const Environment env(p);
    auto sample = [&](int i) -> std::optional<glm::vec3> {
      Sampler rng(SamplerKind::independent, i, 0, 0, 23);
      float pdf;
      const vec3 d = env.sample(rng.next2(), pdf);
      if (!(pdf > 0.0f)) return std::nullopt;
      EXPECT_NEAR(pdf, env.pdf(d), 1e-3f * pdf);
      return d;
    };
    auto pdf = [&](const glm::vec3& d) { return env.pdf(d); };
    const test::ChiSquareResult r = test::chi_square_test(sample, pdf, 400000, 32, 64);
    EXPECT_GT(r.p_value, 1e-3) << "chi2 " << r.statistic << " dof " << r.dof;
    EXPECT_NEAR(r.pdf_integral, 1.0, 2e-3);
    EXPECT_NEAR(r.sampled_fraction, 1.0, 1e-9);
  }
}

// A white Lambertian floor under the environment: its radiance is 1/pi times the cosine-
// weighted integral of the environment over the upper hemisphere, which quadrature over the
// directions gives independently of the renderer's sampling. Light sampling of the image,
// BSDF sampling and their MIS weights must reproduce it.
TEST(Environment, LambertianFloorUnderTheSkyMatchesQuadrature) {
  EnvironmentParams p;
  p.image_path = write_test_environment("env-floor");
  p.image = read_environment_image(p.image_path);
  SceneDescription scene;
  test::add_mesh(scene, test::make_quad({0, 0, 0}, {50, 0, 0}, {0, 0, -50}, test::add_material(scene, test::diffuse(vec3(1.0f)))));
  RenderScene rs(std::move(scene), p);
  double irradiance = 0.0;  // the red channel
  const int n = 1000;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < 2 * n; ++j) {
      const double c = (i + 0.5) / n, phi = (j + 0.5) / (2 * n) * 2 * M_PI, s = std::sqrt(1 - c * c);
      irradiance += rs.environment.radiance(vec3(s * std::cos(phi), c, s * std::sin(phi))).r * c;
    }
  irradiance *= (1.0 / n) * (2 * M_PI / (2 * n));
  RenderSettings st;
  st.width = st.height = 8;
  st.spp = 256;
  st.max_bounces = 1;
  const FrameImage img = render_frame(rs, make_camera(test::look_at({0, 1, 0.5f}, {0, 0, 0}, 1.0f), 8, 8, {}), st).image;
  double mean = 0.0, var = 0.0;
  for (std::size_t i = 0; i < img.rgb.size(); i += 3) mean += img.rgb[i];
  mean /= 64;
  for (std::size_t i = 0; i < img.rgb.size(); i += 3) var += (img.rgb[i] - mean) * (img.rgb[i] - mean);
  var /= 63;
  const double expected = irradiance / M_PI;
  EXPECT_NEAR(mean, expected, 4.0 * std::sqrt(var / 64) + 2e-3 * expected);
  // Cosine-weighted BSDF sampling alone finds the 9-texel sun in ~2% of samples: about 50%
  // noise per pixel at 256 spp. Sampling the image must do several times better.
  EXPECT_LT(std::sqrt(var), 0.15 * expected);
}

}  // namespace
}  // namespace tessera
