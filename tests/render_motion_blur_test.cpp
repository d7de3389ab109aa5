// Motion blur, rendered: an emissive quad sweeping across an orthographic view leaves the
// trapezoid its time-averaged coverage predicts and keeps its integral, whether the quad
// moves as a placement, deforms, or the camera moves instead; a turning bar blurs along arcs
// (rotation interpolated as rotation); a moving light is sampled where it is; and a scene
// that does not move renders exactly as it did, bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include <glm/gtc/matrix_transform.hpp>

#include "renderer/render/render.h"
#include "tests/same_bits.h"
#include "tests/scene_builders.h"

namespace tessera {
namespace {

glm::mat4 translate(float x, float y = 0.0f, float z = 0.0f) { return glm::translate(glm::mat4(1.0f), vec3(x, y, z)); }

// An orthographic camera at z = 2 looking down -z at the x-y plane, `half_w` x `half_h`.
Camera ortho(float half_w, float half_h) {
  Camera cam;
  cam.projection = Camera::Projection::Orthographic;
  cam.xmag = half_w;
  cam.ymag = half_h;
  cam.camera_to_world = translate(0.0f, 0.0f, 2.0f);
  return cam;
}

RenderSettings box_settings(int width, int height, int spp) {
  RenderSettings s;
  s.width = width;
  s.height = height;
  s.spp = spp;
  s.max_bounces = 0;  // the emitter only: every sample is 0 or 1
  s.filter = {PixelFilterKind::box, 0.0f};  // each sample uniform in its own pixel's square
  return s;
}

FrameImage render(SceneDescription scene, const Camera& cam, const RenderSettings& s) {
  EnvironmentParams env;
  env.background = vec3(0.0f);
  RenderScene rs(std::move(scene), env);
  return render_frame(rs, make_camera(cam, s.width, s.height, {}), s).image;
}

float red(const FrameImage& img, int x, int y) { return img.rgb[3 * (y * img.width + x)]; }

// ---- The sweeping quad -------------------------------------------------------------------
// A 64 x 16 image of x in [-2, 2], y in [-0.5, 0.5]: 1/16 unit per pixel. The quad (radiance
// 1, half extents kHx, kHy) moves its centre from x = start to start + kDist at constant speed
// over the shutter. None of its edges falls on a pixel boundary.
constexpr int kW = 64, kH = 16, kSpp = 1024;
constexpr float kHx = 0.26f, kHy = 0.24f, kDist = 1.5f, kStart = -0.97f;

SceneDescription quad_scene(float start, int steps) {
  SceneDescription d;
  d.motion_steps = steps;
  test::add_mesh(d, test::make_quad({0, 0, 0}, {kHx, 0, 0}, {0, kHy, 0}, test::add_material(d, test::emitter(vec3(1.0f)))),
                 {translate(start)});
  return d;
}

// The quad placed at `start` whose placement moves kDist along x (`dist` < 0: the other way).
SceneDescription moving_placement(float start, float dist) {
  SceneDescription d = quad_scene(start, 3);
  d.instances[0].motion = {translate(start + 0.5f * dist), translate(start + dist)};
  return d;
}

// The same motion as a deforming mesh: its corners at each step, placed once where it stands.
SceneDescription deforming_mesh(float start, float dist) {
  SceneDescription d = quad_scene(start, 3);
  TriangleMesh& m = d.meshes[0].primitives[0];
  for (float f : {0.5f, 1.0f}) {
    MeshArray<vec3> p = m.positions;
    for (vec3& v : p) v.x += f * dist;
    m.motion_positions.push_back(p);
  }
  return d;
}

// Length of [lo, hi] within [a, b].
double overlap(double lo, double hi, double a, double b) { return std::max(0.0, std::min(hi, b) - std::max(lo, a)); }

// The time-averaged coverage g(x) of a segment of half-width h whose centre sweeps [a, b]
// uniformly is |[x - h, x + h] within [a, b]| / (b - a): a trapezoid, linear between its
// kinks at a -+ h and b -+ h. Its mean over [x0, x1] exactly: the trapezoid rule between kinks.
double swept_mean(double x0, double x1, double h, double a, double b) {
  auto g = [&](double x) { return overlap(x - h, x + h, a, b) / (b - a); };
  std::vector<double> cuts = {x0, x1};
  for (double k : {a - h, a + h, b - h, b + h})
    if (k > x0 && k < x1) cuts.push_back(k);
  std::sort(cuts.begin(), cuts.end());
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) sum += 0.5 * (g(cuts[i]) + g(cuts[i + 1])) * (cuts[i + 1] - cuts[i]);
  return sum / (x1 - x0);
}

// Pixel (x, y)'s expected value for the quad's centre sweeping [a, b]: the sweep along x
// times the share of the row inside |y| <= kHy.
double expected_pixel(int x, int y, double a, double b) {
  const double px = 4.0 / kW;
  const double x0 = -2.0 + x * px, y1 = 0.5 - y * px;
  return swept_mean(x0, x0 + px, kHx, a, b) * overlap(y1 - px, y1, -kHy, kHy) / px;
}

// The image against the closed form: zero exactly where nothing passes, each column's sum
// along the motion's profile within 4 standard errors (64 columns are compared), and the
// whole image's sum (radiance x pixel area) within 3 of the static quad's emission x area in
// pixels. Every sample is 0 or 1, so a pixel's variance is at most p (1 - p) / spp
// (stratified samples give less).
void expect_swept_quad(const FrameImage& img, double a, double b, const char* what) {
  double total = 0.0, total_expected = 0.0, total_var = 0.0;
  for (int x = 0; x < kW; ++x) {
    double column = 0.0, expected = 0.0, var = 0.0;
    for (int y = 0; y < kH; ++y) {
      const double e = expected_pixel(x, y, a, b);
      if (e == 0.0) {
        ASSERT_EQ(red(img, x, y), 0.0f) << what << ": pixel " << x << ", " << y << " is outside the sweep";
      }
      column += red(img, x, y);
      expected += e;
      var += e * (1.0 - e) / kSpp;
    }
    EXPECT_NEAR(column, expected, 4.0 * std::sqrt(var) + 1e-6) << what << ": column " << x;
    total += column;
    total_expected += expected;
    total_var += var;
  }
  const double px = 4.0 / kW;
  EXPECT_NEAR(total_expected, (2 * kHx / px) * (2 * kHy / px), 1e-3);  // 8.32 x 7.68 pixels
  EXPECT_NEAR(total, total_expected, 3.0 * std::sqrt(total_var)) << what;
}

TEST(RenderMotionBlur, MovingQuadSweepsTheClosedFormTrapezoid) {
  const FrameImage img = render(moving_placement(kStart, kDist), ortho(2.0f, 0.5f), box_settings(kW, kH, kSpp));
  expect_swept_quad(img, kStart, kStart + kDist, "moving placement");
  // The plateau between the ramps: the quad covers a point there for 2 kHx / kDist of the time.
  EXPECT_NEAR(red(img, 27, 8), 2 * kHx / kDist, 0.03);
}

TEST(RenderMotionBlur, DeformingQuadSweepsTheSameTrapezoid) {
  expect_swept_quad(render(deforming_mesh(kStart, kDist), ortho(2.0f, 0.5f), box_settings(kW, kH, kSpp)), kStart,
                    kStart + kDist, "deforming mesh");
}

// The camera moving +kDist over a still quad sees what a still camera sees of the quad moving
// -kDist: the same samples (film, lens, time) meet the same relative geometry, so the images
// agree sample for sample but where rounding moves an edge by an ulp.
TEST(RenderMotionBlur, MovingCameraBlursAsTheQuadMovingTheOtherWay) {
  const float start = 0.5f;
  Camera moving = ortho(2.0f, 0.5f);
  moving.motion = {translate(0.5f * kDist, 0.0f, 2.0f), translate(kDist, 0.0f, 2.0f)};
  SceneDescription still = quad_scene(start, 3);
  const FrameImage by_camera = render(still, moving, box_settings(kW, kH, kSpp));
  const FrameImage by_quad = render(moving_placement(start, -kDist), ortho(2.0f, 0.5f), box_settings(kW, kH, kSpp));
  expect_swept_quad(by_camera, start - kDist, start, "moving camera");
  expect_swept_quad(by_quad, start - kDist, start, "quad moving the other way");
  double differing = 0.0;
  for (std::size_t i = 0; i < by_camera.rgb.size(); i += 3) {
    EXPECT_LE(std::fabs(by_camera.rgb[i] - by_quad.rgb[i]), 2.0f / kSpp) << "pixel " << i / 3;
    differing += std::fabs(by_camera.rgb[i] - by_quad.rgb[i]) * kSpp;
  }
  EXPECT_LE(differing, 8.0);  // samples that fell the other side of an edge, in the whole image
}

// ---- The turning bar ---------------------------------------------------------------------
// A bar x in [0, 1], |y| <= kB turns about the z axis from 0 to 90 degrees over the shutter,
// given at 3 steps (0, 45, 90 degrees). A point at radius r and angle phi is covered while
// the bar's angle theta has phi - theta in S = {lo <= |delta| <= a}: a = asin(kB / r) (pi/2
// within kB of the axis), lo = acos(1 / r) beyond the bar's end. Theta is uniform on [0, pi/2].
constexpr float kB = 0.1f;
constexpr int kBarPx = 64, kBarSpp = 512;
constexpr double kHalfView = 1.1;

double bar_coverage(double x, double y) {
  const double r = std::hypot(x, y), phi = std::atan2(y, x), quarter = M_PI / 2;
  const double a = r <= kB ? quarter : std::asin(kB / r);
  const double lo = r > 1.0 ? std::acos(1.0 / r) : 0.0;
  if (lo > a) return 0.0;
  // theta in [phi - a, phi - lo] or [phi + lo, phi + a], within [0, pi/2]
  return (overlap(phi - a, phi - lo, 0.0, quarter) + overlap(phi + lo, phi + a, 0.0, quarter)) / quarter;
}

// The pixel's mean coverage by an n x n midpoint rule (the coverage is continuous).
double bar_pixel(int px, int py, int n) {
  const double size = 2 * kHalfView / kBarPx;
  double sum = 0.0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      sum += bar_coverage(-kHalfView + (px + (i + 0.5) / n) * size, kHalfView - (py + (j + 0.5) / n) * size);
  return sum / (n * n);
}

TEST(RenderMotionBlur, TurningBarBlursAlongArcs) {
  SceneDescription d;
  d.motion_steps = 3;
  test::add_mesh(d, test::make_quad({0.5f, 0, 0}, {0.5f, 0, 0}, {0, kB, 0}, test::add_material(d, test::emitter(vec3(1.0f)))));
  auto turn = [](float deg) { return glm::rotate(glm::mat4(1.0f), glm::radians(deg), vec3(0, 0, 1)); };
  d.instances[0].motion = {turn(45.0f), turn(90.0f)};
  const FrameImage img = render(d, ortho(kHalfView, kHalfView), box_settings(kBarPx, kBarPx, kBarSpp));
  // The expected image, and the quadrature's error bounded by the change from 16 x 16 points.
  std::vector<double> expected(kBarPx * kBarPx), quadrature(kBarPx * kBarPx);
  for (int py = 0; py < kBarPx; ++py)
    for (int px = 0; px < kBarPx; ++px) {
      expected[py * kBarPx + px] = bar_pixel(px, py, 32);
      quadrature[py * kBarPx + px] = std::fabs(expected[py * kBarPx + px] - bar_pixel(px, py, 16));
    }
  auto never_covered = [&](int px, int py) {  // nor any neighbour: clear of the swept region
    for (int j = std::max(py - 1, 0); j <= std::min(py + 1, kBarPx - 1); ++j)
      for (int i = std::max(px - 1, 0); i <= std::min(px + 1, kBarPx - 1); ++i)
        if (expected[j * kBarPx + i] > 0.0) return false;
    return true;
  };
  // Sums over rings (0.1 wide) and 15-degree sectors of the pixels whose centres fall there,
  // each within 4 standard errors (88 bins are compared) and the quadrature's error.
  const double size = 2 * kHalfView / kBarPx;
  constexpr int kRings = 11, kSectors = 8;  // sectors from -15 to 105 degrees
  double got[kRings][kSectors] = {}, want[kRings][kSectors] = {}, var[kRings][kSectors] = {}, slack[kRings][kSectors] = {};
  double arc_sum = 0.0, arc_want = 0.0, arc_var = 0.0;
  int arc_pixels = 0;
  for (int py = 0; py < kBarPx; ++py) {
    for (int px = 0; px < kBarPx; ++px) {
      const double x = -kHalfView + (px + 0.5) * size, y = kHalfView - (py + 0.5) * size;
      const double e = expected[py * kBarPx + px], v = red(img, px, py);
      if (never_covered(px, py)) {
        ASSERT_EQ(v, 0.0f) << "pixel " << px << ", " << py << " is never covered";
      }
      const double r = std::hypot(x, y), deg = glm::degrees(std::atan2(y, x));
      const int ring = static_cast<int>(r / 0.1), sector = static_cast<int>(std::floor((deg + 15.0) / 15.0));
      if (ring < kRings && sector >= 0 && sector < kSectors) {
        got[ring][sector] += v;
        want[ring][sector] += e;
        var[ring][sector] += e * (1.0 - e) / kBarSpp;
        slack[ring][sector] += quadrature[py * kBarPx + px];
      }
      // Halfway between two steps, near the bar's end: averaging the matrices would shrink
      // the bar there to cos(22.5 deg) = 0.924 of its length (0.933 at its corners) and
      // leave these pixels (all of each beyond r = 0.936) dark.
      if (r > 0.96 && r < 0.976 && deg > 16.0 && deg < 29.0) {
        arc_sum += v;
        arc_want += e;
        arc_var += e * (1.0 - e) / kBarSpp;
        ++arc_pixels;
      }
    }
  }
  for (int i = 0; i < kRings; ++i)
    for (int j = 0; j < kSectors; ++j)
      EXPECT_NEAR(got[i][j], want[i][j], 4.0 * std::sqrt(var[i][j]) + slack[i][j] + 1e-3) << "ring " << i << ", sector " << j;
  ASSERT_GE(arc_pixels, 2);
  EXPECT_NEAR(arc_want / arc_pixels, 2 * std::asin(kB / 0.968) / (M_PI / 2), 0.01);  // the arc's value, 0.13
  EXPECT_NEAR(arc_sum, arc_want, 4.0 * std::sqrt(arc_var));
  EXPECT_GT(arc_sum / arc_pixels, 0.08);
}

// ---- Light sampling at the path's time ---------------------------------------------------
// A diffuse floor (albedo 0.5) under a square emitter (half side 0.2, radiance 4, height 0.5,
// facing down) that moves from x = -0.6 to 0.6, or grows from half side 0.2 to 0.4, over the
// shutter; direct light only. A floor point's radiance is albedo x Le x F, F the form factor of
// the emitter's rectangle as it is then (sum of signed corner factors, Howell C-11), averaged
// over the shutter. Light sampling, BSDF sampling and MIS must each give it.
constexpr float kLe = 4.0f, kHeight = 0.5f, kHalf = 0.2f;
constexpr int kFloorPx = 40, kFloorSpp = 256;

double corner_factor(double x, double y) {
  return (x / std::sqrt(1 + x * x) * std::atan(y / std::sqrt(1 + x * x)) +
          y / std::sqrt(1 + y * y) * std::atan(x / std::sqrt(1 + y * y))) / (2 * M_PI);
}

// The form factor from floor point (x, z) to the emitter [x0, x1] x [z0, z1] above it.
double rectangle_factor(double x, double z, double x0, double x1, double z0, double z1) {
  auto c = [&](double a, double b) { return corner_factor((a - x) / kHeight, (b - z) / kHeight); };
  return c(x1, z1) - c(x0, z1) - c(x1, z0) + c(x0, z0);
}

// The emitter's centre and half side at time t.
using Emitter = std::function<void(double t, double& cx, double& half)>;

double floor_radiance(double x, double z, const Emitter& emitter) {
  double sum = 0.0;  // Simpson over the shutter: the integrand is smooth
  constexpr int n = 64;
  for (int i = 0; i <= n; ++i) {
    double cx, half;
    emitter(static_cast<double>(i) / n, cx, half);
    const double w = i == 0 || i == n ? 1 : (i % 2 ? 4 : 2);
    sum += w * rectangle_factor(x, z, cx - half, cx + half, -half, half);
  }
  return 0.5 * kLe * sum / (3.0 * n);
}

SceneDescription lit_floor(bool grows) {
  SceneDescription d;
  d.motion_steps = 2;
  test::add_mesh(d, test::make_quad({0, 0, 0}, {2, 0, 0}, {0, 0, -2}, test::add_material(d, test::diffuse(vec3(0.5f)))));
  const int light = test::add_material(d, test::emitter(vec3(kLe)));
  if (grows) {
    TriangleMesh m = test::make_quad({0, kHeight, 0}, {kHalf, 0, 0}, {0, 0, kHalf}, light);
    MeshArray<vec3> p = m.positions;
    for (vec3& v : p) v = vec3(2.0f * v.x, v.y, 2.0f * v.z);
    m.motion_positions = {p};
    test::add_mesh(d, m);
  } else {
    test::add_mesh(d, test::make_quad({0, 0, 0}, {kHalf, 0, 0}, {0, 0, kHalf}, light), {translate(-0.6f, kHeight)});
    d.instances.back().motion = {translate(0.6f, kHeight)};
  }
  return d;
}

// Residuals (image - closed form) in four strips across x: their means and standard errors.
struct Strips {
  double mean[4] = {}, error[4] = {};
};

Strips floor_strips(bool grows, LightSampling mode, LightTreeUse tree = LightTreeUse::Off) {
  Camera cam;  // below the emitter, looking straight down: the floor unoccluded, x right, z down
  cam.projection = Camera::Projection::Orthographic;
  cam.xmag = cam.ymag = 1.0f;
  cam.camera_to_world = glm::inverse(glm::lookAtRH(vec3(0, 0.25f, 0), vec3(0, 0, 0), vec3(0, 0, -1)));
  RenderSettings s;
  s.width = s.height = kFloorPx;
  s.spp = kFloorSpp;
  s.max_bounces = 1;  // direct light
  s.light_sampling = mode;
  s.light_tree = tree;
  s.filter = {PixelFilterKind::box, 0.0f};
  const FrameImage img = render(lit_floor(grows), cam, s);
  const Emitter emitter = [grows](double t, double& cx, double& half) {
    cx = grows ? 0.0 : -0.6 + 1.2 * t;
    half = grows ? kHalf * (1.0 + t) : kHalf;
  };
  std::vector<double> residuals[4];
  const double size = 2.0 / kFloorPx;
  for (int py = 0; py < kFloorPx; ++py) {
    for (int px = 0; px < kFloorPx; ++px) {
      double e = 0.0;  // the pixel's mean over a 3 x 3 grid
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i)
          e += floor_radiance(-1.0 + (px + (i + 0.5) / 3) * size, -1.0 + (py + (j + 0.5) / 3) * size, emitter) / 9;
      residuals[px * 4 / kFloorPx].push_back(red(img, px, py) - e);
    }
  }
  Strips st;
  for (int k = 0; k < 4; ++k) {
    const std::vector<double>& r = residuals[k];
    double mean = 0.0, var = 0.0;
    for (double v : r) mean += v / r.size();
    for (double v : r) var += (v - mean) * (v - mean) / (r.size() - 1);
    st.mean[k] = mean;
    st.error[k] = std::sqrt(var / r.size());
  }
  return st;
}

void expect_light_sampling_agrees(bool grows, LightTreeUse tree = LightTreeUse::Off) {
  const char* names[] = {"mis", "bsdf", "lights"};
  const LightSampling modes[] = {LightSampling::Mis, LightSampling::BsdfOnly, LightSampling::LightsOnly};
  for (int m = 0; m < 3; ++m) {
    const Strips st = floor_strips(grows, modes[m], tree);
    for (int k = 0; k < 4; ++k) {
      // The floor's radiance there is 0.05 to 0.3: the test resolves a few thousandths.
      EXPECT_LT(st.error[k], 0.004) << names[m] << ", strip " << k;
      EXPECT_NEAR(st.mean[k], 0.0, 4.0 * st.error[k] + 1e-4) << (grows ? "growing" : "moving") << " emitter, "
                                                             << names[m] << ", strip " << k;
    }
  }
}

TEST(RenderMotionBlur, MovingLightIsSampledWhereItIsAtThePathsTime) { expect_light_sampling_agrees(false); }

// The emitters' light tree bounds a moving or deforming triangle over the whole shutter: a
// light sample chosen by it, and its MIS weight, agree with the closed form too.
TEST(RenderMotionBlur, MovingAndGrowingLightsAgreeWithTheEmitterTree) {
  expect_light_sampling_agrees(false, LightTreeUse::On);
  expect_light_sampling_agrees(true, LightTreeUse::On);
}

TEST(RenderMotionBlur, GrowingLightIsSampledWithItsAreaAtThePathsTime) { expect_light_sampling_agrees(true); }

// Punctual lights follow their node over the shutter. A point light of 1 cd at height h slides
// from x = -a to x = a above a floor of albedo rho: the floor's radiance is rho / pi times the
// time-averaged irradiance, h / (2a) [u / (c^2 sqrt(u^2 + c^2))] from u = -a - x to a - x, with
// c^2 = h^2 + z^2. A directional light of 1 lux tilting from -theta to theta about z (slerp:
// the angle linear in time) gives rho / pi sin(theta) / theta everywhere.
TEST(RenderMotionBlur, PunctualLightsMoveWithTheirNodes) {
  constexpr double kRho = 0.5, kA = 0.6, kH = 0.5, kTheta = 1.0;
  auto floor_scene = [&](const PunctualLight& light) {
    SceneDescription d;
    d.motion_steps = 2;
    test::add_mesh(d, test::make_quad({0, 0, 0}, {2, 0, 0}, {0, 0, -2}, test::add_material(d, test::diffuse(vec3(kRho)))));
    d.lights.push_back(light);
    return d;
  };
  Camera cam;  // looking straight down at the floor: x right, z down
  cam.projection = Camera::Projection::Orthographic;
  cam.xmag = cam.ymag = 1.0f;
  cam.camera_to_world = glm::inverse(glm::lookAtRH(vec3(0, 0.25f, 0), vec3(0, 0, 0), vec3(0, 0, -1)));
  RenderSettings s;
  s.width = s.height = kFloorPx;
  s.spp = 64;
  s.max_bounces = 1;
  s.filter = {PixelFilterKind::box, 0.0f};

  PunctualLight point;
  point.light_to_world = translate(-kA, kH);
  point.position = vec3(point.light_to_world[3]);
  point.motion = {translate(kA, kH)};
  const FrameImage img = render(floor_scene(point), cam, s);
  auto expected = [&](double x, double z) {
    const double c2 = kH * kH + z * z;
    auto f = [&](double u) { return u / (c2 * std::sqrt(u * u + c2)); };
    return kRho / M_PI * kH / (2 * kA) * (f(kA - x) - f(-kA - x));
  };
  std::vector<double> residuals[4];
  const double size = 2.0 / kFloorPx;
  for (int py = 0; py < kFloorPx; ++py)
    for (int px = 0; px < kFloorPx; ++px) {
      double e = 0.0;  // the pixel's mean over a 3 x 3 grid
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) e += expected(-1.0 + (px + (i + 0.5) / 3) * size, -1.0 + (py + (j + 0.5) / 3) * size) / 9;
      residuals[px * 4 / kFloorPx].push_back(red(img, px, py) - e);
    }
  for (int k = 0; k < 4; ++k) {
    const std::vector<double>& r = residuals[k];
    double mean = 0.0, var = 0.0;
    for (double v : r) mean += v / r.size();
    for (double v : r) var += (v - mean) * (v - mean) / (r.size() - 1);
    // The floor's radiance there is 0.05 to 0.5: the test resolves a few thousandths.
    EXPECT_NEAR(mean, 0.0, 4.0 * std::sqrt(var / r.size()) + 1e-4) << "point light, strip " << k;
  }

  PunctualLight sun;
  sun.type = PunctualLight::Type::Directional;
  const glm::mat4 down = glm::rotate(glm::mat4(1.0f), float(-M_PI / 2), vec3(1, 0, 0));  // -Z to -Y
  sun.light_to_world = glm::rotate(glm::mat4(1.0f), float(-kTheta), vec3(0, 0, 1)) * down;
  sun.direction = glm::normalize(-vec3(sun.light_to_world[2]));
  sun.motion = {glm::rotate(glm::mat4(1.0f), float(kTheta), vec3(0, 0, 1)) * down};
  const FrameImage lit = render(floor_scene(sun), cam, s);
  double mean = 0.0;
  for (int i = 0; i < kFloorPx * kFloorPx; ++i) mean += lit.rgb[3 * i] / (kFloorPx * kFloorPx);
  EXPECT_NEAR(mean, kRho / M_PI * std::sin(kTheta) / kTheta, 2e-4) << "tilting directional light";
}

// ---- Bits ----------------------------------------------------------------------------------
// A room with a swelling sphere placed twice (one placement moving and turning), a deforming
// wall, a moving emitter, a point light, depth of field and a moving camera.
SceneDescription busy_room(int steps, bool still) {
  SceneDescription d;
  d.motion_steps = steps;
  const int white = test::add_material(d, test::diffuse(vec3(0.7f)));
  const int light = test::add_material(d, test::emitter(vec3(8.0f)));
  test::add_mesh(d, test::make_quad({0, -1, 0}, {1, 0, 0}, {0, 0, -1}, white));
  TriangleMesh wall = test::make_quad({0, 0, -1}, {1, 0, 0}, {0, 1, 0}, white);
  MeshArray<vec3> bent = wall.positions;
  for (vec3& v : bent) v.z += 0.3f * v.x * v.y;
  wall.motion_positions.assign(steps - 1, bent);
  test::add_mesh(d, wall);
  TriangleMesh sphere = test::make_sphere({0, 0, 0}, 0.25f, 2, white);
  MeshArray<vec3> swollen = sphere.positions;
  for (vec3& v : swollen) v *= 1.3f;
  sphere.motion_positions.assign(steps - 1, swollen);
  test::add_mesh(d, sphere, {translate(-0.4f, -0.7f, 0.2f), translate(0.4f, -0.7f, -0.3f)});
  d.instances.back().motion.assign(steps - 1, translate(0.2f, -0.5f, -0.3f) * glm::rotate(glm::mat4(1.0f), 1.0f, vec3(0, 1, 0)));
  test::add_mesh(d, test::make_quad({0, 0.99f, 0}, {0.3f, 0, 0}, {0, 0, 0.3f}, light));
  d.instances.back().motion.assign(steps - 1, translate(0.4f, 0.0f, 0.0f));
  PunctualLight point;
  point.position = {0.5f, 0.5f, 0.5f};
  point.intensity = 2.0f;
  d.lights.push_back(point);
  if (still)
    for (Instance& inst : d.instances) inst.motion.assign(inst.motion.size(), inst.object_to_world);
  if (still)
    for (Mesh& mesh : d.meshes) {
      TriangleMesh& m = mesh.primitives[0];
      if (m.deforms()) m.motion_positions.assign(steps - 1, m.positions);
    }
  return d;
}

FrameImage render_room(const SceneDescription& d, int threads, int tile_size, bool camera_moves,
                       FilmState* resume = nullptr, std::vector<FilmState>* checkpoints = nullptr) {
  RenderSettings s;
  s.width = 41;
  s.height = 29;
  s.spp = 7;  // waves of 1, 2, 4
  s.max_bounces = 6;
  s.threads = threads;
  s.tile_size = tile_size;
  s.seed = 77;
  s.aovs = {true, true, true};
  if (checkpoints) {
    s.checkpoint_interval = 0.0;
    s.on_checkpoint = [checkpoints](const Film& film, const RenderStats&) { checkpoints->push_back(film.state()); };
  }
  Camera cam = test::look_at({0, 0, 3}, {0, 0, 0}, 45.0f);
  if (camera_moves) cam.motion.assign(d.motion_steps - 1, translate(0.2f, 0.1f, 0.0f) * cam.camera_to_world);
  EnvironmentParams env;
  env.background = vec3(0.2f);
  RenderScene rs(d, env);
  return render_frame(rs, make_camera(cam, s.width, s.height, {0.0f, 0.05f, 3.0f}), s, nullptr, resume).image;
}

TEST(RenderMotionBlur, NoShutterOrNoMovementRendersExactlyAsWithoutMotion) {
  SceneDescription plain = busy_room(3, false);
  for (Instance& inst : plain.instances) inst.motion.clear();
  for (Mesh& mesh : plain.meshes) mesh.primitives[0].motion_positions.clear();
  plain.motion_steps = 1;
  const FrameImage reference = render_room(plain, 2, 16, false);
  SceneDescription closed = busy_room(3, false);
  closed.motion_steps = 1;  // motion given, but no shutter: everything at its opening
  test::expect_same_image(reference, render_room(closed, 2, 16, false));
  test::expect_same_image(reference, render_room(busy_room(3, true), 2, 16, false));  // steps that move nothing
  const FrameImage blurred = render_room(busy_room(3, false), 2, 16, false);
  EXPECT_FALSE(test::same_bits(reference.rgb, blurred.rgb));
}

TEST(RenderMotionBlur, BlurredImageIsTheSameForAnyThreadsTilesAndAfterResume) {
  const SceneDescription d = busy_room(3, false);
  const FrameImage whole = render_room(d, 1, 32, true);
  test::expect_same_image(whole, render_room(d, 2, 32, true));
  test::expect_same_image(render_room(d, 2, 8, true), render_room(d, 2, 64, true));
  test::expect_same_image(whole, render_room(d, 2, 8, true));
  std::vector<FilmState> checkpoints;
  render_room(d, 2, 16, true, nullptr, &checkpoints);
  ASSERT_EQ(checkpoints.size(), 2u);
  test::expect_same_image(whole, render_room(d, 1, 5, true, &checkpoints[1]));
}

}  // namespace
}  // namespace tessera
