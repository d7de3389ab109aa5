// KHR_materials_dispersion through the whole renderer: a glass wedge splits the edge of a
// bright half-plane behind it into colours, each channel's edge where Snell's law with the
// Cauchy index puts that channel's wavelengths.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "renderer/bsdfs/spectrum.h"
#include "renderer/render/render.h"
#include "tests/scene_builders.h"

namespace tessera {
namespace {

// The scene, in the x-z plane (extruded along y): an orthographic camera looking down -z sees
// x in [-0.5, 0.5] through a wedge whose front face is the plane z = 0 (rays enter at normal
// incidence: no deviation there) and whose back face z = -(t0 + x tan A) meets them at the
// apex angle A; they leave bent toward +x by delta(n) = asin(n sin A) - A and reach, at
// z = -L, an emitter of radiance 1 covering x > x0. Black elsewhere.
constexpr float kApex = 0.349066f;  // 20 degrees
constexpr float kT0 = 0.6f, kL = 3.0f, kX0 = 0.463f;
constexpr float kIor = 1.5f, kDispersion = 2.0f;  // Abbe number 10
constexpr int kWidth = 256, kHeight = 16;

// Adds the quad p0 p1 p2 p3 with its front face toward `outward`.
void add_face(TriangleMesh& m, vec3 p0, vec3 p1, vec3 p2, vec3 p3, vec3 outward) {
  if (glm::dot(glm::cross(p1 - p0, p2 - p0), outward) < 0.0f) std::swap(p1, p3);
  const auto base = static_cast<std::uint32_t>(m.positions.size());
  m.positions.insert(m.positions.end(), {p0, p1, p2, p3});
  m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

SceneDescription wedge_scene(float dispersion) {
  SceneDescription scene;
  Material glass = test::diffuse(vec3(1.0f));
  glass.specular_factor = 1.0f;
  glass.roughness_factor = 0.0f;
  glass.transmission_factor = 1.0f;
  glass.thickness_factor = 1.0f;
  glass.ior = kIor;
  glass.dispersion = dispersion;
  TriangleMesh wedge;
  wedge.material = test::add_material(scene, glass);
  const float t = std::tan(kApex), h = 3.0f;
  auto front = [&](float x, float y) { return vec3(x, y, 0.0f); };
  auto back = [&](float x, float y) { return vec3(x, y, -(kT0 + x * t)); };
  add_face(wedge, front(-1, -h), front(1, -h), front(1, h), front(-1, h), {0, 0, 1});
  add_face(wedge, back(-1, -h), back(1, -h), back(1, h), back(-1, h), {-std::sin(kApex), 0, -std::cos(kApex)});
  add_face(wedge, front(-1, -h), back(-1, -h), back(-1, h), front(-1, h), {-1, 0, 0});
  add_face(wedge, front(1, -h), back(1, -h), back(1, h), front(1, h), {1, 0, 0});
  add_face(wedge, front(-1, h), front(1, h), back(1, h), back(-1, h), {0, 1, 0});
  add_face(wedge, front(-1, -h), front(1, -h), back(1, -h), back(-1, -h), {0, -1, 0});
  test::add_mesh(scene, wedge);
  test::add_mesh(scene, test::make_quad({kX0 + 5.0f, 0.0f, -kL}, {5.0f, 0.0f, 0.0f}, {0.0f, 5.0f, 0.0f},
                                        test::add_material(scene, test::emitter(vec3(1.0f)))));
  return scene;
}

// Where a camera ray at x lands on the emitter's plane for index n.
double landing(double x, double n) {
  const double delta = std::asin(n * std::sin(kApex)) - kApex;
  return x + (kL - kT0 - x * std::tan(kApex)) * std::tan(delta);
}

// The share of channel c's spectral weight that a ray at x carries onto the emitter.
double lit_share(double x, int c) {
  double lit = 0.0, all = 0.0;
  for (float lambda = kLambdaMin + 0.5f; lambda < kLambdaMax; lambda += 1.0f) {
    const double w = wavelength_response(lambda)[c];
    all += w;
    if (landing(x, dispersive_ior(kIor, kDispersion, lambda)) > kX0) lit += w;
  }
  return lit / all;
}

// The x where a profile crosses half its plateau, from pixel centres (linear between them).
double half_crossing(const std::vector<double>& profile, double plateau) {
  for (int i = 0; i + 1 < kWidth; ++i) {
    const double a = profile[i] / plateau, b = profile[i + 1] / plateau;
    if (a < 0.5 && b >= 0.5) {
      const double px = i + (0.5 - a) / (b - a);
      return ((px + 0.5) / (kWidth / 2.0) - 1.0) * 0.5;
    }
  }
  return NAN;
}

std::vector<double> channel_profile(const FrameImage& img, int c) {
  std::vector<double> p(kWidth, 0.0);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) p[x] += img.rgb[3 * (y * kWidth + x) + c] / kHeight;
  return p;
}

FrameImage render_wedge(float dispersion) {
  Camera cam;
  cam.projection = Camera::Projection::Orthographic;
  cam.xmag = 0.5f;
  cam.ymag = 0.5f * kHeight / kWidth;
  cam.camera_to_world = glm::translate(glm::mat4(1.0f), vec3(0.0f, 0.0f, 2.0f));
  RenderSettings s;
  s.width = kWidth;
  s.height = kHeight;
  s.spp = 256;
  s.max_bounces = 8;
  EnvironmentParams env;
  env.background = vec3(0.0f);
  RenderScene rs(wedge_scene(dispersion), env);
  return render_frame(rs, make_camera(cam, s.width, s.height, {}), s).image;
}

TEST(RenderDispersion, WedgeSplitsAnEdgeWhereSnellAndCauchyPutEachChannel) {
  const FrameImage img = render_wedge(kDispersion);
  double edge[3];
  for (int c = 0; c < 3; ++c) {
    const std::vector<double> p = channel_profile(img, c);
    double plateau = 0.0;  // the right end: every wavelength lands on the emitter
    for (int x = kWidth - 32; x < kWidth; ++x) plateau += p[x] / 32;
    ASSERT_GT(plateau, 0.8) << "channel " << c;  // what the two faces transmit (about 0.92)
    edge[c] = half_crossing(p, plateau);
    double expected = 0.0;  // bisection of lit_share = 1/2
    for (double lo = -0.5, hi = 0.5; hi - lo > 1e-6; expected = 0.5 * (lo + hi))
      (lit_share(0.5 * (lo + hi), c) < 0.5 ? lo : hi) = 0.5 * (lo + hi);
    const double pixel = 1.0 / kWidth;
    EXPECT_NEAR(edge[c], expected, 1.0 * pixel) << "channel " << c;
  }
  // Blue bends most: its edge lies left of green's, green's left of red's, pixels apart.
  EXPECT_GT(edge[0] - edge[2], 5.0 / kWidth);
  EXPECT_GT(edge[0], edge[1]);
  EXPECT_GT(edge[1], edge[2]);
}

TEST(RenderDispersion, WithoutDispersionTheChannelsShareOneEdge) {
  const FrameImage img = render_wedge(0.0f);
  double edge[3];
  for (int c = 0; c < 3; ++c) {
    const std::vector<double> p = channel_profile(img, c);
    double plateau = 0.0;
    for (int x = kWidth - 32; x < kWidth; ++x) plateau += p[x] / 32;
    edge[c] = half_crossing(p, plateau);
  }
  EXPECT_NEAR(edge[0], edge[2], 0.25 / kWidth);
  double expected = 0.0;  // landing(x, 1.5) = x0, by bisection
  for (double lo = -0.5, hi = 0.5; hi - lo > 1e-7; expected = 0.5 * (lo + hi))
    (landing(0.5 * (lo + hi), kIor) < kX0 ? lo : hi) = 0.5 * (lo + hi);
  EXPECT_NEAR(edge[1], expected, 0.5 / kWidth);
}

}  // namespace
}  // namespace tessera
