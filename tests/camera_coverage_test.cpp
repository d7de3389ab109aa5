// CameraCoverage: the pixels it leaves out really see nothing (checked by tracing dense rays
// over each one's whole filter footprint and margin, lens and shutter), it leaves out what it
// should (the sky above a floor that runs under and behind the camera), it gives up where it
// must (the camera or its lens inside the geometry's box, a moving camera with a lens), and a render that
// skips those pixels' rays is the same bit for bit as one that traces them all, for every
// camera, filter, crop, background and motion it applies to.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "renderer/camera/camera_coverage.h"
#include "renderer/render/render.h"
#include "tests/same_bits.h"
#include "tests/scene_builders.h"
#include "imageio/environment_image.h"

namespace tessera {
namespace {

// A small sphere and a tilted quad over a floor from z = -20 to z = +20 (under and behind
// the camera at z = 5), and a quad behind the camera facing it.
SceneDescription product_shot() {
  SceneDescription d;
  const int grey = test::add_material(d, test::diffuse(vec3(0.6f)));
  test::add_mesh(d, test::make_sphere({0.4f, 0.2f, 0}, 0.5f, 2, grey));
  test::add_mesh(d, test::make_quad({-1.2f, 0.6f, -1}, {0.3f, 0.1f, 0}, {0, 0.3f, 0.2f}, grey));
  test::add_mesh(d, test::make_quad({0, -1, 0}, {20, 0, 0}, {0, 0, -20}, grey));
  test::add_mesh(d, test::make_quad({0, 0, 8}, {1, 0, 0}, {0, 1, 0}, grey));
  return d;
}

// The scene `Make` describes under a white world, built once.
template <SceneDescription (*Make)()>
RenderScene& in_white_world() {
  static RenderScene* scene = [] {
    EnvironmentParams env;
    env.background = vec3(1.0f);
    return new RenderScene(Make(), env);
  }();
  return *scene;
}

RenderScene& shot_scene() { return in_white_world<product_shot>(); }

CameraCoverageParams whole_frame(int w, int h, float radius) {
  CameraCoverageParams p;
  p.full_width = p.width = w;
  p.full_height = p.height = h;
  p.filter_radius = radius;
  return p;
}

// Every pixel left out, traced for real: a grid of rays over its filter footprint (where its
// samples can land; 9x9, or 5x5 through a lens or in a moving scene), through a lens from a
// 5x5 grid of lens positions that reaches the disk's rim, in a moving scene at nine times
// over the shutter, hits nothing. Returns the number of pixels left out.
int expect_left_out_pixels_see_nothing(const RenderScene& scene, const RenderCamera& cam, const CameraCoverageParams& p) {
  const CameraCoverage coverage(cam, *scene.geometry, p);
  const bool lens = cam.lens_radius > 0.0f, moves = scene.geometry->moves();
  const int film_n = lens || moves ? 5 : 9, lens_n = lens ? 5 : 1, time_n = moves ? 9 : 1;
  int left_out = 0, wrong = 0;
  for (int y = p.y0; y < p.y0 + p.height; ++y)
    for (int x = p.x0; x < p.x0 + p.width; ++x) {
      if (coverage.may_hit(x, y)) continue;
      ++left_out;
      const float reach = p.filter_radius;
      for (int i = 0; i < film_n; ++i)
        for (int j = 0; j < film_n; ++j)
          for (int k = 0; k < lens_n * lens_n * time_n; ++k) {
            const float step = 2.0f * reach / (film_n - 1);
            const vec2 at(x + 0.5f - reach + step * i, y + 0.5f - reach + step * j);
            const int l = k % (lens_n * lens_n);
            const vec2 on_lens = lens ? vec2(l % lens_n, l / lens_n) * (0.9999999f / (lens_n - 1)) : vec2(0.5f);
            const float time = moves ? float(k / (lens_n * lens_n)) * (0.9999999f / (time_n - 1)) : 0.0f;
            HitRecord hit;
            const Ray ray = cam.generate_ray({at.x / p.full_width, at.y / p.full_height}, on_lens, time);
            if (scene.geometry->intersect(ray, hit) && wrong++ == 0)
              ADD_FAILURE() << "pixel " << x << "," << y << " left out, but a ray hits at time " << time;
          }
    }
  EXPECT_EQ(wrong, 0);
  EXPECT_EQ(coverage.empty_pixels(), static_cast<std::uint64_t>(left_out));
  return left_out;
}

TEST(CameraCoverage, PixelsLeftOutSeeNothingAndTheSkyIsLeftOut) {
  const int w = 80, h = 60;
  const RenderCamera cam = make_camera(test::look_at({0, 0, 5}, {0, 0, 0}, 40.0f), w, h, {});
  const int left_out = expect_left_out_pixels_see_nothing(shot_scene(), cam, whole_frame(w, h, 0.75f));
  // The floor's horizon is the middle row (the camera looks level from y = 0, the floor at
  // y = -1 reaches 15 units beyond the target): the upper half is sky but for the sphere's
  // and the quad's boxes, whose projections take less than a third of it.
  EXPECT_GT(left_out, w * h / 2 * 2 / 3);
  EXPECT_LT(left_out, w * h / 2);
}

TEST(CameraCoverage, WideFiltersCropsAndOrthographicCamerasLeaveOutOnlyEmptyPixels) {
  const int w = 64, h = 48;
  const RenderCamera tilted = make_camera(test::look_at({3, 1.5f, 4}, {0, 0, 0}, 30.0f), w, h, {});
  EXPECT_GT(expect_left_out_pixels_see_nothing(shot_scene(), tilted, whole_frame(w, h, 2.0f)), 0);
  CameraCoverageParams crop = whole_frame(w, h, 0.5f);
  crop.x0 = 10, crop.y0 = 2, crop.width = 40, crop.height = 8;
  EXPECT_GT(expect_left_out_pixels_see_nothing(shot_scene(), tilted, crop), 0);
  Camera ortho = test::look_at({0, 0.5f, 5}, {0, 0.5f, 0}, 40.0f);
  ortho.projection = Camera::Projection::Orthographic;
  ortho.xmag = ortho.ymag = 2.0f;
  EXPECT_GT(expect_left_out_pixels_see_nothing(shot_scene(), make_camera(ortho, w, h, {}), whole_frame(w, h, 0.75f)), 0);
}

TEST(CameraCoverage, NothingIsLeftOutWhereItCannotBeKnown) {
  const int w = 32, h = 24;
  // Inside the floor's box (it is flat, so widened only by rounding's slack): nothing is known.
  const RenderCamera on_floor = make_camera(test::look_at({0, -1, 5}, {0, 2, 0}, 40.0f), w, h, {});
  EXPECT_EQ(CameraCoverage(on_floor, *shot_scene().geometry, whole_frame(w, h, 0.5f)).empty_pixels(), 0u);
  // A lens as wide as the camera's height over the floor reaches into the floor's box.
  CameraParams wide;
  wide.aperture = 2.2f;
  wide.focus_distance = 5.0f;
  const RenderCamera lens_at_floor = make_camera(test::look_at({0, 0, 5}, {0, 0, 0}, 40.0f), w, h, wide);
  EXPECT_EQ(CameraCoverage(lens_at_floor, *shot_scene().geometry, whole_frame(w, h, 0.5f)).empty_pixels(), 0u);
}

CameraParams thin_lens(float aperture, float focus_distance) {
  CameraParams lens;
  lens.aperture = aperture;
  lens.focus_distance = focus_distance;
  return lens;
}

// Through a lens the boxes' rectangles grow by the defocus blur at their depths: the pixels
// left out still see nothing from any point of the lens, and there are fewer of them the wider
// the lens and the further the focus from the objects.
TEST(CameraCoverage, ThroughALensPixelsLeftOutSeeNothing) {
  const int w = 32, h = 24;
  const Camera level = test::look_at({0, 0, 5}, {0, 0, 0}, 40.0f);
  const CameraCoverageParams frame = whole_frame(w, h, 0.75f);
  const int pinhole = expect_left_out_pixels_see_nothing(shot_scene(), make_camera(level, w, h, {}), frame);
  const int focused = expect_left_out_pixels_see_nothing(shot_scene(), make_camera(level, w, h, thin_lens(0.2f, 5.0f)), frame);
  const int far_focus = expect_left_out_pixels_see_nothing(shot_scene(), make_camera(level, w, h, thin_lens(0.2f, 50.0f)), frame);
  const int wide = expect_left_out_pixels_see_nothing(shot_scene(), make_camera(level, w, h, thin_lens(0.6f, 5.0f)), frame);
  EXPECT_GT(wide, 0);
  EXPECT_LT(focused, pinhole);
  EXPECT_LT(far_focus, focused);
  EXPECT_LT(wide, focused);
  Camera ortho = test::look_at({0, 0.5f, 5}, {0, 0.5f, 0}, 40.0f);
  ortho.projection = Camera::Projection::Orthographic;
  ortho.xmag = ortho.ymag = 2.0f;
  EXPECT_GT(expect_left_out_pixels_see_nothing(shot_scene(), make_camera(ortho, w, h, thin_lens(0.3f, 3.0f)), frame), 0);
  const Camera tilted = test::look_at({3, 1.5f, 4}, {0, 0, 0}, 30.0f);
  EXPECT_GT(expect_left_out_pixels_see_nothing(shot_scene(), make_camera(tilted, w, h, thin_lens(0.05f, 5.0f)), frame), 0);
}

glm::mat4 translate(float x, float y, float z) { return glm::translate(glm::mat4(1.0f), vec3(x, y, z)); }

// product_shot over a three-step shutter: the sphere (its vertices away from its node's
// origin, so that turning sweeps it round) slides and turns 143 degrees per step (its path
// leaves the box of each step's two ends), the tilted quad bends, the floor stands still.
SceneDescription moving_shot() {
  SceneDescription d;
  d.motion_steps = 3;
  const int grey = test::add_material(d, test::diffuse(vec3(0.6f)));
  test::add_mesh(d, test::make_sphere({0.8f, 0, 0}, 0.25f, 2, grey), {translate(0.1f, 0.2f, 0)});
  d.instances.back().motion = {translate(0.2f, 0.3f, 0) * glm::rotate(glm::mat4(1.0f), 2.5f, vec3(0, 0, 1)),
                               translate(0.3f, 0.4f, 0) * glm::rotate(glm::mat4(1.0f), 5.0f, vec3(0, 0, 1))};
  TriangleMesh quad = test::make_quad({-1.2f, 0.6f, -1}, {0.3f, 0.1f, 0}, {0, 0.3f, 0.2f}, grey);
  MeshArray<vec3> bent = quad.positions;
  for (vec3& v : bent) v.y += 0.4f * (v.x + 1.2f);
  quad.motion_positions = {bent, bent};
  test::add_mesh(d, quad, {glm::mat4(1.0f), translate(0, 0, 0)});  // placed twice: an instanced mesh
  test::add_mesh(d, test::make_quad({0, -1, 0}, {20, 0, 0}, {0, 0, -20}, grey));
  return d;
}

RenderScene& moving_scene() { return in_white_world<moving_shot>(); }

// Moving triangles are covered where they are at any time the shutter is open: the pixels
// left out see nothing at nine times over it, and fewer are left out than when it is closed.
TEST(CameraCoverage, InAMovingScenePixelsLeftOutSeeNothingAtAnyTime) {
  const int w = 40, h = 30;
  ASSERT_TRUE(moving_scene().geometry->moves());
  const RenderCamera level = make_camera(test::look_at({0, 0, 5}, {0, 0, 0}, 40.0f), w, h, {});
  const int moving = expect_left_out_pixels_see_nothing(moving_scene(), level, whole_frame(w, h, 0.75f));
  SceneDescription closed = moving_shot();
  closed.motion_steps = 1;  // everything where it is at the opening
  const RenderScene still(closed, EnvironmentParams{});
  const int at_opening = expect_left_out_pixels_see_nothing(still, level, whole_frame(w, h, 0.75f));
  EXPECT_GT(moving, 0);
  EXPECT_LT(moving, at_opening);
  CameraParams lens;
  lens.aperture = 0.2f;
  lens.focus_distance = 4.0f;
  EXPECT_GT(expect_left_out_pixels_see_nothing(moving_scene(), make_camera(test::look_at({2, 1, 5}, {0, 0, 0}, 40.0f), w, h, lens),
                                               whole_frame(w, h, 1.5f)),
            0);
}

RenderResult render(const RenderScene& scene, const Camera& camera, RenderSettings s, bool cull,
                    const CameraParams& lens = {}) {
  s.cull_camera_rays = cull;
  const int fw = s.window.cropped() ? s.window.full_width : s.width, fh = s.window.cropped() ? s.window.full_height : s.height;
  return render_frame(scene, make_camera(camera, fw, fh, lens), s);
}

void expect_same_render_with_fewer_rays(const RenderScene& scene, const Camera& camera, const RenderSettings& s,
                                        const CameraParams& lens = {}) {
  SCOPED_TRACE(testing::Message() << s.width << "x" << s.height << " filter " << describe(s.filter) << " aperture "
                                  << lens.aperture);
  const RenderResult all = render(scene, camera, s, false, lens), culled = render(scene, camera, s, true, lens);
  test::expect_same_image(all.image, culled.image);
  EXPECT_LT(culled.stats.rays, all.stats.rays);
}

RenderSettings small_settings() {
  RenderSettings s;
  s.width = 40, s.height = 30, s.spp = 20, s.threads = 2, s.seed = 5;
  s.aovs = {true, true, true, true};
  return s;
}

TEST(CameraCoverage, RenderIsTheSameBitForBitWithAndWithoutCulling) {
  const Camera level = test::look_at({0, 0, 5}, {0, 0, 0}, 40.0f);
  expect_same_render_with_fewer_rays(shot_scene(), level, small_settings());
  RenderSettings gaussian = small_settings();
  gaussian.filter = {PixelFilterKind::gaussian, 3.0f};
  gaussian.sampler = SamplerKind::independent;
  expect_same_render_with_fewer_rays(shot_scene(), level, gaussian);
  RenderSettings crop = small_settings();
  crop.width = 40, crop.height = 8;
  crop.window = {10, 2, 64, 48};
  crop.filter = {PixelFilterKind::box, 1.0f};
  expect_same_render_with_fewer_rays(shot_scene(), test::look_at({3, 1.5f, 4}, {0, 0, 0}, 30.0f), crop);
  RenderSettings transparent = small_settings();
  transparent.aovs.coverage = true;
  Camera ortho = level;
  ortho.projection = Camera::Projection::Orthographic;
  ortho.xmag = ortho.ymag = 2.0f;
  expect_same_render_with_fewer_rays(shot_scene(), ortho, transparent);
  expect_same_render_with_fewer_rays(shot_scene(), level, small_settings(), thin_lens(0.2f, 3.0f));
}

// A camera that slides (a twentieth of its height over the floor) and pans (1.7 degrees a
// step) over a three-step shutter.
Camera panning_camera() {
  const Camera level = test::look_at({0, 0, 5}, {0, 0, 0}, 40.0f);
  Camera moving = level;
  const glm::mat4 pan = glm::rotate(glm::mat4(1.0f), 0.03f, vec3(0, 1, 0));
  moving.motion = {translate(0.03f, 0.01f, 0) * level.camera_to_world * pan,
                   translate(0.05f, 0.01f, 0.03f) * level.camera_to_world * pan * pan};
  return moving;
}

// A moving camera is bounded from each pair of steps' halfway pose: the pixels left out see
// nothing at nine times over the shutter, fewer than for a still camera; with a lens, or
// turning too far to bound, nothing is left out.
TEST(CameraCoverage, AMovingCameraLeavesOutOnlyPixelsThatSeeNothingAtAnyTime) {
  const int w = 40, h = 30;
  const RenderCamera still = make_camera(test::look_at({0, 0, 5}, {0, 0, 0}, 40.0f), w, h, {});
  const RenderCamera moving = make_camera(panning_camera(), w, h, {});
  ASSERT_TRUE(moving.moves());
  const int left_still = expect_left_out_pixels_see_nothing(moving_scene(), still, whole_frame(w, h, 0.75f));
  const int left_moving = expect_left_out_pixels_see_nothing(moving_scene(), moving, whole_frame(w, h, 0.75f));
  EXPECT_GT(left_moving, 0);
  EXPECT_LT(left_moving, left_still);
  EXPECT_GT(expect_left_out_pixels_see_nothing(shot_scene(), moving, whole_frame(w, h, 1.5f)), 0);
  CameraParams lens;
  lens.aperture = 0.1f;
  lens.focus_distance = 5.0f;
  EXPECT_EQ(CameraCoverage(make_camera(panning_camera(), w, h, lens), *moving_scene().geometry, whole_frame(w, h, 0.5f))
                .empty_pixels(),
            0u);
  Camera spinning = panning_camera();
  spinning.motion = {spinning.camera_to_world * glm::rotate(glm::mat4(1.0f), 1.2f, vec3(0, 1, 0)),
                     spinning.camera_to_world * glm::rotate(glm::mat4(1.0f), 2.4f, vec3(0, 1, 0))};
  EXPECT_EQ(CameraCoverage(make_camera(spinning, w, h, {}), *moving_scene().geometry, whole_frame(w, h, 0.5f)).empty_pixels(),
            0u);
}

SceneDescription facing_square() {
  SceneDescription d;
  test::add_mesh(d, test::make_quad({0, 0, 0}, {0.5f, 0, 0}, {0, 0.5f, 0}, test::add_material(d, test::diffuse(vec3(0.5f)))));
  return d;
}

// A square facing the camera is its own box, so the bounds are tight: a pan of 2.9 degrees or
// a slide of 0.15 units a step moves it 1-2 pixels, more than the filter's reach; those
// pixels must stay covered (this fails when the turn or the drift is not accounted for).
TEST(CameraCoverage, AMovingCameraCoversWhereItsTurnAndDriftCarryTheGeometry) {
  const int w = 40, h = 30;
  const Camera level = test::look_at({0, 0, 5}, {0, 0, 0}, 40.0f);
  Camera pan = level, slide = level;
  const glm::mat4 turn = glm::rotate(glm::mat4(1.0f), 0.05f, vec3(0, 1, 0));
  pan.motion = {level.camera_to_world * turn, level.camera_to_world * turn * turn};
  slide.motion = {translate(0.15f, 0.05f, 0) * level.camera_to_world, translate(0.3f, 0.1f, 0) * level.camera_to_world};
  const RenderScene& square = in_white_world<facing_square>();
  EXPECT_GT(expect_left_out_pixels_see_nothing(square, make_camera(pan, w, h, {}), whole_frame(w, h, 0.5f)), w * h / 2);
  EXPECT_GT(expect_left_out_pixels_see_nothing(square, make_camera(slide, w, h, {}), whole_frame(w, h, 0.5f)), w * h / 2);
}

TEST(CameraCoverage, MotionBlurRendersTheSameWithAStillOrAMovingCamera) {
  expect_same_render_with_fewer_rays(moving_scene(), test::look_at({0, 0, 5}, {0, 0, 0}, 40.0f), small_settings());
  expect_same_render_with_fewer_rays(moving_scene(), panning_camera(), small_settings());
  expect_same_render_with_fewer_rays(shot_scene(), panning_camera(), small_settings());
}

TEST(CameraCoverage, EnvironmentImageAndNonFiniteBackgroundRenderTheSame) {
  EnvironmentParams env;
  env.image_path = std::string(TESSERA_SOURCE_DIR) + "/scenes/env/spruit_sunrise_1k.hdr";
  env.image = read_environment_image(env.image_path);
  env.rotate_degrees = 30.0f;
  const RenderScene lit(product_shot(), env);
  expect_same_render_with_fewer_rays(lit, test::look_at({0, 0, 5}, {0, 0, 0}, 40.0f), small_settings());
  expect_same_render_with_fewer_rays(lit, test::look_at({0, 0, 5}, {0, 0, 0}, 40.0f), small_settings(),
                                     thin_lens(0.3f, 2.0f));
  EnvironmentParams bad;
  bad.background = vec3(std::numeric_limits<float>::infinity());
  const RenderScene broken(product_shot(), bad);
  const Camera level = test::look_at({0, 0, 5}, {0, 0, 0}, 40.0f);
  const RenderResult all = render(broken, level, small_settings(), false), culled = render(broken, level, small_settings(), true);
  test::expect_same_image(all.image, culled.image);
  EXPECT_EQ(all.stats.dropped_samples, culled.stats.dropped_samples);
  EXPECT_GT(culled.stats.dropped_samples, 0u);
}

}  // namespace
}  // namespace tessera
