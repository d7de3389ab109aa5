// The `--background auto` rule (app/frame/auto_background.h): black only when the scene's own
// lights can light it. Expected powers are worked out by hand from the geometry:
// tests/data/bulb_on_body.gltf (validator-clean) is a 2 m box with a 2 cm single-sided
// emissive square (radiance 1) 1 cm above it, so its emitters give pi x 0.0004 against
// pi x 24.08 (the bounding box 2 x 2.01 x 2) from a white background: 0.00166%.
#include <gtest/gtest.h>

#include <string>

#include "app/frame/auto_background.h"
#include "scene_io/gltf_loader.h"
#include "tests/exr_read.h"
#include "tests/scene_builders.h"
#include "tests/test_support.h"

namespace tessera {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(AutoBackground, TinyBulbOnALargeUnlitBodyKeepsWhite) {
  const SceneDescription s = load_gltf(test::data_path("bulb_on_body.gltf")).scene;
  EXPECT_NEAR(untextured_emitter_power(s), kPi * 0.0004, 1e-9);
  EXPECT_NEAR(white_background_power(s), kPi * 24.08, 1e-4);
  const AutoBackground b = choose_auto_background(s);
  EXPECT_FALSE(b.black);
  EXPECT_EQ(b.why, "emitters give 0.00166% of the power a white background would");
}

TEST(AutoBackground, CornellBoxCeilingLightKeepsBlack) {
  const AutoBackground b = choose_auto_background(load_gltf(test::scene_path("cornell-box/cornell-box.gltf")).scene);
  EXPECT_TRUE(b.black) << b.why;
}

TEST(AutoBackground, PunctualLightsMakeItBlackAndNoLightWhite) {
  SceneDescription s;
  test::add_mesh(s, test::make_quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, test::add_material(s, test::diffuse({0.5f, 0.5f, 0.5f}))));
  s.bounds.extend({-1, -1, 0});
  s.bounds.extend({1, 1, 0});
  EXPECT_EQ(choose_auto_background(s).why, "no lights");
  EXPECT_FALSE(choose_auto_background(s).black);
  s.lights.emplace_back();
  EXPECT_EQ(choose_auto_background(s).why, "1 punctual light");
  EXPECT_TRUE(choose_auto_background(s).black);
}

TEST(AutoBackground, EmittersOfAMeaningfulShareMakeItBlack) {
  // A 2 x 2 emitter of radiance L on a 2 x 2 floor: the box is flat (area 2 x 4), so the
  // share is L x 4 / 8 (one-sided); black from L = 0.02 (1%).
  for (float l : {0.019f, 0.021f}) {
    SceneDescription s;
    test::add_mesh(s, test::make_quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, test::add_material(s, test::emitter(glm::vec3(l)))));
    s.bounds.extend({-1, -1, 0});
    s.bounds.extend({1, 1, 0});
    EXPECT_EQ(choose_auto_background(s).black, l > 0.02f) << l << ": " << choose_auto_background(s).why;
  }
}

TEST(AutoBackground, RenderSaysWhichItChoseAndTheBackgroundIsWhite) {
  const std::string out = test::make_temp_dir("auto_background") + "/bulb.exr";
  const test::CommandResult r = test::run_command(test::tessera_exe() + " render '" + test::data_path("bulb_on_body.gltf") +
                                                  "' --width 16 --spp 1 -o '" + out + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("; background white (auto: emitters give 0.00166% of the power a white background would)\n"),
            std::string::npos)
      << r.err;
  const std::vector<float> rgb = test::exr_rgb(out);
  ASSERT_GE(rgb.size(), 3u);
  EXPECT_EQ(rgb[0], 1.0f);  // the top-left corner sees the sky: the automatic camera frames the box
}

}  // namespace
}  // namespace tessera
