// The view transform of display-format previews (imageio/display_transform.*): the built-in
// views against their formulas, a studio's OCIO config against OCIO's own processor and the
// config's own formula, and the command line end to end.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include <OpenColorIO/OpenColorIO.h>
#include <OpenImageIO/imageio.h>

#include "imageio/display_transform.h"
#include "tests/exr_read.h"
#include "tests/test_support.h"

namespace tessera {
namespace {

namespace OCIO = OCIO_NAMESPACE;

double srgb_encode(double v) { return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055; }
int code(double display) { return static_cast<int>(std::clamp(display, 0.0, 1.0) * 255.0 + 0.5); }

// Grey levels from 1/1024 to 64 (16 stops) in sixteenth stops, and 0.
std::vector<float> ramp() {
  std::vector<float> rgb(3, 0.0f);
  for (int i = 0; i <= 256; ++i) rgb.insert(rgb.end(), 3, std::exp2(-10.0f + i / 16.0f));
  return rgb;
}

TEST(DisplayTransform, StandardIsTheSrgbEncodingOfTheClippedValue) {
  const std::vector<float> in = ramp();
  const std::vector<std::uint8_t> out = to_display_rgb8(in, 0.0f, {ViewTransform::standard});
  for (std::size_t i = 0; i < in.size(); ++i)
    EXPECT_NEAR(out[i], code(srgb_encode(std::min(in[i], 1.0f))), 1) << in[i];
  // Exposure is a factor before the view: +1 stop of 0.25 is 0.5.
  EXPECT_EQ(to_display_rgb8({0.25f, 0.25f, 0.25f}, 1.0f, {ViewTransform::standard})[0],
            to_display_rgb8({0.5f, 0.5f, 0.5f}, 0.0f, {ViewTransform::standard})[0]);
}

// Filmic: the tone curve (Narkowicz's ACES fit) then sRGB, to a code (the curve is tabulated
// over a log2 shaper in OCIO: within one code). Highlights roll off rather than clip.
TEST(DisplayTransform, FilmicFollowsItsToneCurveAndKeepsHighlights) {
  const std::vector<float> in = ramp();
  const std::vector<std::uint8_t> out = to_display_rgb8(in, 0.0f, {ViewTransform::filmic});
  for (std::size_t i = 3; i < in.size(); ++i) {
    const double x = in[i], aces = x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14);
    EXPECT_NEAR(out[i], code(srgb_encode(std::min(aces, 1.0))), 1) << x;
    EXPECT_GE(out[i], out[i >= 6 ? i - 3 : i]) << "not monotonic at " << x;
  }
  EXPECT_EQ(out[0], 0);  // black stays black
  const auto grey = [](float v, ViewTransform view) { return to_display_rgb8({v, v, v}, 0.0f, {view})[0]; };
  EXPECT_EQ(grey(2.0f, ViewTransform::standard), 255);  // clipped
  EXPECT_LT(grey(2.0f, ViewTransform::filmic), 250);  // still has room: 2 and 4 differ
  EXPECT_LT(grey(2.0f, ViewTransform::filmic), grey(4.0f, ViewTransform::filmic));
}

// A config with a display "Test" and views "Gamma" (x^(1/2.2)) and "Raw".
std::string write_config(const std::string& dir) {
  const std::string path = dir + "/test.ocio";
  std::ofstream(path) << R"(ocio_profile_version: 2
roles:
  default: linear
  scene_linear: linear
file_rules:
  - !<Rule> {name: Default, colorspace: linear}
displays:
  Test:
    - !<View> {name: Gamma, colorspace: gamma22}
    - !<View> {name: Raw, colorspace: linear}
colorspaces:
  - !<ColorSpace>
    name: linear
  - !<ColorSpace>
    name: gamma22
    from_scene_reference: !<ExponentTransform> {value: 2.2, direction: inverse}
)";
  return path;
}

TEST(DisplayTransform, AConfigsViewIsWhatOcioGivesForIt) {
  const std::string config = write_config(test::make_temp_dir("ocio-config"));
  const std::vector<float> in = ramp();
  const std::vector<std::uint8_t> out = to_display_rgb8(in, 0.0f, {ViewTransform::filmic, config, "Test", "Gamma"});
  auto cpu = OCIO::Config::CreateFromFile(config.c_str())
                 ->getProcessor(OCIO::ROLE_SCENE_LINEAR, "Test", "Gamma", OCIO::TRANSFORM_DIR_FORWARD)
                 ->getDefaultCPUProcessor();
  for (std::size_t i = 0; i < in.size(); i += 3) {
    float px[3] = {in[i], in[i + 1], in[i + 2]};
    cpu->applyRGB(px);
    EXPECT_EQ(out[i], code(px[0])) << in[i];  // OCIO's own processor
    EXPECT_NEAR(out[i], code(std::pow(std::min(in[i], 1.0f), 1.0 / 2.2)), 1) << in[i];  // the config's formula
  }
  // The display's default view is the first: Gamma.
  EXPECT_EQ(to_display_rgb8(in, 0.0f, {ViewTransform::filmic, config, "", ""}), out);
  EXPECT_THROW(check_display_transform({ViewTransform::filmic, config, "Test", "Nope"}), DisplayTransformError);
}

std::string quote(const std::string& s) { return "'" + s + "'"; }

// End to end: the preview is the EXR's radiance through the chosen view; bad configs and
// views exit 2 naming them, before rendering.
TEST(DisplayTransform, ThePreviewIsTheExrThroughTheView) {
  const std::string dir = test::make_temp_dir("ocio-cli");
  const std::string config = write_config(dir);
  const std::string base = quote(test::tessera_exe()) + " render " + quote(test::scene_path("cornell-box/cornell-box.gltf")) +
                           " --width 24 --spp 4 -q -o " + quote(dir + "/f.exr") + " --preview " + quote(dir + "/f.png");
  const auto r = test::run_command(base + " --ocio-config " + quote(config) + " --ocio-view Gamma");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<float> hdr = test::exr_rgb(dir + "/f.exr");
  auto png = OIIO::ImageInput::open(dir + "/f.png");
  ASSERT_TRUE(png);
  std::vector<std::uint8_t> codes(hdr.size());
  ASSERT_TRUE(png->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, codes.data()));
  for (std::size_t i = 0; i < hdr.size(); ++i) EXPECT_NEAR(codes[i], code(std::pow(std::min(hdr[i], 1.0f), 1.0 / 2.2)), 1);

  const auto view = test::run_command(base + " --ocio-config " + quote(config) + " --ocio-view Log");
  EXPECT_EQ(view.exit_code, 2);
  EXPECT_NE(view.err.find("display 'Test' has no view 'Log' (it has Gamma, Raw)"), std::string::npos) << view.err;
  std::ofstream(dir + "/bad.ocio") << "ocio_profile_version: 2\ncolorspaces: [oops\n";
  const auto bad = test::run_command(base + " --ocio-config " + quote(dir + "/bad.ocio"));
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find(dir + "/bad.ocio: not a usable OpenColorIO config"), std::string::npos) << bad.err;
  const auto lone = test::run_command(base + " --ocio-view Gamma");
  EXPECT_EQ(lone.exit_code, 2);
  EXPECT_NE(lone.err.find("--ocio-config, which is not given"), std::string::npos) << lone.err;
}

}  // namespace
}  // namespace tessera
