// The sampler in whole renders: a floor under a square emitter (direct light by light and
// BSDF sampling with MIS, the pixel jitter across a flat irradiance field) against its
// closed form. With independent samples the error falls as N^-1/2. With the Sobol sampler
// every draw of a pixel (light point and choice, BSDF direction and lobe) is stratified; the
// light-sampled part is smooth, the BSDF-sampled part has an edge (the emitter's outline on
// the hemisphere: hit or miss), for which scrambled nets give a variance of O(N^-3/2), so
// the error must fall at least about as N^-3/4. The test fits the slope of the
// root-mean-square error over 49 pixels (49 independent scramblings) against N.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "renderer/render/render.h"
#include "tests/scene_builders.h"

namespace tessera {
namespace {

using test::add_material;
using test::add_mesh;

double error_slope(SamplerKind sampler) {
  const float a = 0.25f, h = 1.0f, le = 4.0f, albedo = 0.5f;
  SceneDescription scene;
  add_mesh(scene, test::make_quad({0, 0, 0}, {5, 0, 0}, {0, 0, -5}, add_material(scene, test::diffuse(vec3(albedo)))));
  add_mesh(scene, test::make_quad({0, h, 0}, {a, 0, 0}, {0, 0, a}, add_material(scene, test::emitter(vec3(le)))));
  EnvironmentParams env;
  env.background = vec3(0.0f);
  const RenderScene rs(std::move(scene), env);
  const double expected = test::floor_under_square_emitter(a, h, le, albedo);
  std::vector<double> log_n, log_e;
  for (int spp = 16; spp <= 1024; spp *= 4) {
    RenderSettings s;
    s.width = s.height = 7;  // a 0.01 degree field: the irradiance is flat to 1e-5 over it
    s.spp = spp;
    s.max_bounces = 1;
    s.sampler = sampler;
    const FrameImage img =
        render_frame(rs, make_camera(test::look_at({0, 0.5f, 3}, {0, 0, 0}, 0.01f), s.width, s.height, {}), s).image;
    double sq = 0.0;
    for (std::size_t i = 0; i < img.rgb.size(); i += 3) sq += std::pow(img.rgb[i] - expected, 2);
    log_n.push_back(std::log(double(spp)));
    log_e.push_back(0.5 * std::log(sq / (img.rgb.size() / 3)));
  }
  const double k = static_cast<double>(log_n.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < log_n.size(); ++i)
    sx += log_n[i], sy += log_e[i], sxx += log_n[i] * log_n[i], sxy += log_n[i] * log_e[i];
  return (k * sxy - sx * sy) / (k * sxx - sx * sx);
}

TEST(RenderSampler, SobolErrorFallsFasterThanIndependentUnderAnAreaLight) {
  const double independent = error_slope(SamplerKind::independent), sobol = error_slope(SamplerKind::sobol);
  EXPECT_NEAR(independent, -0.5, 0.15);
  EXPECT_LT(sobol, -0.8) << "independent: " << independent;  // measured: -0.92
}

}  // namespace
}  // namespace tessera
