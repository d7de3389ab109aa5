// Unbiasedness of the light-transport estimators: BSDF sampling alone, light sampling alone
// and their combination by MIS converge to the same image. The scene has a small and a large
// emitter over a glossy and a diffuse floor, and an environment image, so each strategy is
// poor somewhere (a small light is hard to hit, a glossy lobe hard to light-sample).
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <memory>

#include <glm/gtc/matrix_transform.hpp>

#include "renderer/render/render.h"
#include "tests/scene_builders.h"
#include "tests/test_support.h"
#include "imageio/environment_image.h"

namespace tessera {
namespace {

RenderScene& scene() {
  static RenderScene* rs = [] {
    SceneDescription s;
    Material glossy = test::diffuse(vec3(0.7f));
    glossy.specular_factor = 1.0f;
    glossy.roughness_factor = 0.3f;
    test::add_mesh(s, test::make_quad({-1, 0, 0}, {1, 0, 0}, {0, 0, -2}, test::add_material(s, test::diffuse(vec3(0.7f)))));
    test::add_mesh(s, test::make_quad({1, 0, 0}, {1, 0, 0}, {0, 0, -2}, test::add_material(s, glossy)));
    Material small = test::emitter(vec3(60.0f));
    test::add_mesh(s, test::make_quad({-0.8f, 1.2f, 0}, {0.05f, 0, 0}, {0, 0, 0.05f}, test::add_material(s, small)));
    Material large = test::emitter(vec3(0.6f));
    test::add_mesh(s, test::make_quad({0.8f, 1.5f, 0}, {0.8f, 0, 0}, {0, 0, 0.8f}, test::add_material(s, large)));
    // A dim sky with a brighter band, so the environment is sampled too.
    const int w = 32, h = 16;
    std::vector<float> px(3 * w * h);
    for (int i = 0; i < w * h; ++i)
      for (int c = 0; c < 3; ++c) px[3 * i + c] = (i / w == 4 ? 2.0f : 0.1f);
    const std::string path = test::make_temp_dir("strategies") + "/sky.exr";
    auto out = OIIO::ImageOutput::create(path);
    out->open(path, OIIO::ImageSpec(w, h, 3, OIIO::TypeDesc::FLOAT));
    out->write_image(OIIO::TypeDesc::FLOAT, px.data());
    out->close();
    EnvironmentParams env;
    env.image_path = path;
    env.image = read_environment_image(env.image_path);
    return new RenderScene(std::move(s), env);
  }();
  return *rs;
}

// Means of the red channel over four image quadrants, and their standard errors. The noise
// is measured from two renders with different seeds: their pixel difference is pure noise,
// free of the image's own variation.
struct Estimate {
  double mean[4] = {}, error[4] = {};
};

// A textured emitter (light sampling reads its emission from the light's own record of the
// triangle's texture coordinates, not the mesh), read through TEXCOORD_1 and placed twice,
// over a diffuse floor: an emissive texture bright at one end and dim at the other.
RenderScene& textured_emitter_scene() {
  static RenderScene* rs = [] {
    SceneDescription s;
    test::add_mesh(s, test::make_quad({0, 0, -0.5f}, {2, 0, 0}, {0, 0, -2}, test::add_material(s, test::diffuse(vec3(0.7f)))));
    Image texture;
    texture.width = 4;
    texture.height = 1;
    texture.channels = 3;
    texture.pixels = std::make_shared<std::vector<std::uint8_t>>(std::vector<std::uint8_t>{255, 255, 255, 180, 120, 60, 40, 40, 200, 10, 10, 10});
    s.images.push_back(texture);
    Material light = test::emitter(vec3(4.0f));
    light.emissive_texture.image = 0;
    light.emissive_texture.texcoord = 1;
    TriangleMesh quad = test::make_quad({0, 0, 0}, {0.4f, 0, 0}, {0, 0, 0.2f}, test::add_material(s, light));
    quad.texcoords1 = {{0.1f, 0.5f}, {0.9f, 0.5f}, {0.9f, 0.4f}, {0.1f, 0.6f}};
    test::add_mesh(s, std::move(quad), {glm::translate(glm::mat4(1.0f), {-0.6f, 1.0f, -0.5f}),
                                        glm::translate(glm::mat4(1.0f), {0.7f, 1.3f, -0.8f})});
    return new RenderScene(std::move(s), EnvironmentParams{});
  }();
  return *rs;
}

std::vector<float> red(const RenderScene& rs, LightSampling mode, int spp, std::uint32_t seed) {
  RenderSettings st;
  st.width = st.height = 32;
  st.spp = spp;
  st.max_bounces = 3;
  st.light_sampling = mode;
  st.seed = seed;
  const Camera cam = test::look_at({0, 2.5f, 3.0f}, {0, 0, -0.5f}, 50.0f);
  const FrameImage img = render_frame(rs, make_camera(cam, st.width, st.height, {}), st).image;
  std::vector<float> r;
  for (std::size_t i = 0; i < img.rgb.size(); i += 3) r.push_back(img.rgb[i]);
  return r;
}

Estimate estimate(const RenderScene& rs, LightSampling mode, int spp) {
  const std::vector<float> a = red(rs, mode, spp, 1), b = red(rs, mode, spp, 2);
  Estimate e;
  for (int q = 0; q < 4; ++q) {
    double sum = 0, diff2 = 0;
    int n = 0;
    for (int y = (q / 2) * 16; y < (q / 2 + 1) * 16; ++y)
      for (int x = (q % 2) * 16; x < (q % 2 + 1) * 16; ++x, ++n) {
        sum += a[y * 32 + x] + b[y * 32 + x];
        diff2 += std::pow(a[y * 32 + x] - b[y * 32 + x], 2);
      }
    e.mean[q] = sum / (2 * n);
    // var(a - b) = 2 var(pixel); the mean of 2n pixels has variance var(pixel) / (2n).
    e.error[q] = std::sqrt(diff2 / n / 2 / (2 * n));
  }
  return e;
}

void expect_strategies_agree(const RenderScene& rs) {
  const Estimate mis = estimate(rs, LightSampling::Mis, 64);
  const Estimate bsdf = estimate(rs, LightSampling::BsdfOnly, 256);
  const Estimate lights = estimate(rs, LightSampling::LightsOnly, 64);
  for (int q = 0; q < 4; ++q) {
    EXPECT_GT(mis.mean[q], 0.0);
    EXPECT_LT(mis.error[q], 0.02 * mis.mean[q]) << "quadrant " << q;  // sharp enough to mean something
    EXPECT_NEAR(mis.mean[q], bsdf.mean[q], 4.0 * std::hypot(mis.error[q], bsdf.error[q])) << "quadrant " << q;
    EXPECT_NEAR(mis.mean[q], lights.mean[q], 4.0 * std::hypot(mis.error[q], lights.error[q])) << "quadrant " << q;
  }
}

TEST(RenderStrategies, BsdfOnlyLightsOnlyAndMisAgree) { expect_strategies_agree(scene()); }

TEST(RenderStrategies, AgreeOnATexturedEmitter) { expect_strategies_agree(textured_emitter_scene()); }

}  // namespace
}  // namespace tessera
