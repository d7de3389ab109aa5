// `tessera denoise` as a user meets it: a file without the half buffers is refused naming
// them (exit 2), and a round trip writes the library's denoised RGB, the input's beauty as
// noisy.R/G/B, every other channel and the header carried over.
#include <gtest/gtest.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <OpenImageIO/imageio.h>

#include "denoiser/denoise.h"
#include "imageio/display_transform.h"
#include "tests/test_support.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;

constexpr int kW = 40, kH = 24;
using Channels = std::map<std::string, std::vector<float>>;

test::CommandResult tessera(const std::string& args) {
  return test::run_command("timeout 120 '" + test::tessera_exe() + "' " + args);
}

// What a render with half buffers writes: noisy halves of a textured image, features,
// feature halves, depth and per-pixel sample counts.
Channels synthetic_frame() {
  Channels ch;
  std::mt19937 rng(7);
  std::normal_distribution<float> noise(0.0f, 0.1f);
  const std::size_t n = static_cast<std::size_t>(kW) * kH;
  for (const char* c : {"R", "G", "B"}) {
    for (const std::string prefix : {"even.", "odd.", "", "Albedo.", "even.Albedo.", "odd.Albedo."})
      ch[prefix + c].resize(n);
  }
  for (const char* c : {"N.X", "N.Y", "N.Z", "even.N.X", "even.N.Y", "even.N.Z", "odd.N.X", "odd.N.Y", "odd.N.Z", "Z", "spp"})
    ch[c].resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const float albedo = (i % kW) < kW / 2 ? 0.2f : 0.7f;
    for (const char* c : {"R", "G", "B"}) {
      ch[std::string("even.") + c][i] = albedo + noise(rng);
      ch[std::string("odd.") + c][i] = albedo + noise(rng);
      ch[c][i] = 0.5f * (ch[std::string("even.") + c][i] + ch[std::string("odd.") + c][i]);
      for (const std::string prefix : {"Albedo.", "even.Albedo.", "odd.Albedo."}) ch[prefix + c][i] = albedo;
    }
    for (const std::string prefix : {"", "even.", "odd."}) ch[prefix + "N.Z"][i] = 1.0f;
    ch["Z"][i] = 3.0f;
    ch["spp"][i] = 8.0f;
  }
  return ch;
}

void write_exr(const std::string& path, Channels& ch, const std::string& sampler = "") {
  Imf::Header header(kW, kH);
  header.insert("samplesPerPixel", Imf::IntAttribute(8));
  if (!sampler.empty()) header.insert("sampler", Imf::StringAttribute(sampler));
  header.insert("scene", Imf::StringAttribute("synthetic"));
  Imf::FrameBuffer fb;
  for (auto& [name, values] : ch) {
    header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    fb.insert(name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(values.data()), sizeof(float), sizeof(float) * kW));
  }
  Imf::OutputFile file(path.c_str(), header);
  file.setFrameBuffer(fb);
  file.writePixels(kH);
}

Channels read_exr(const std::string& path, Imf::Header* header_out = nullptr) {
  Imf::InputFile file(path.c_str());
  Channels ch;
  Imf::FrameBuffer fb;
  for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it) {
    ch[it.name()].resize(static_cast<std::size_t>(kW) * kH);
    fb.insert(it.name(), Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(ch[it.name()].data()), sizeof(float), sizeof(float) * kW));
  }
  file.setFrameBuffer(fb);
  file.readPixels(0, kH - 1);
  if (header_out) *header_out = file.header();
  return ch;
}

std::vector<float> interleave(const Channels& ch, const std::vector<std::string>& names) {
  std::vector<float> out;
  for (std::size_t i = 0; i < static_cast<std::size_t>(kW) * kH; ++i)
    for (const std::string& n : names) out.push_back(ch.at(n)[i]);
  return out;
}

TEST(DenoiseCli, MissingChannelsExit2NamingFileAndChannels) {
  const std::string dir = test::make_temp_dir("denoise-missing");
  Channels ch = synthetic_frame();
  for (const char* c : {"odd.R", "odd.G", "odd.B", "N.Y"}) ch.erase(c);
  const std::string in = dir + "/in.exr", out = dir + "/out.exr";
  write_exr(in, ch);
  const auto r = tessera("denoise '" + in + "' -o '" + out + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "tessera: error: " + in + ": cannot be denoised: missing channels N.Y, odd.R, odd.G, odd.B "
                   "(render it with --denoise, or with --aov halves,albedo,normal)\n");
  EXPECT_FALSE(fs::exists(out));
}

TEST(DenoiseCli, UnreadableInputExits2) {
  const std::string dir = test::make_temp_dir("denoise-unreadable");
  const auto r = tessera("denoise '" + dir + "/none.exr' -o '" + dir + "/out.exr'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err.rfind("tessera: error: " + dir + "/none.exr: cannot be read as an OpenEXR image", 0), 0u) << r.err;
}

// The buffers of a synthetic frame as the library takes them.
DenoiseInput library_input(const Channels& ch) {
  DenoiseInput di;
  di.width = kW, di.height = kH;
  di.color_even = interleave(ch, {"even.R", "even.G", "even.B"});
  di.color_odd = interleave(ch, {"odd.R", "odd.G", "odd.B"});
  di.albedo = interleave(ch, {"Albedo.R", "Albedo.G", "Albedo.B"});
  di.normal = interleave(ch, {"N.X", "N.Y", "N.Z"});
  di.albedo_even = interleave(ch, {"even.Albedo.R", "even.Albedo.G", "even.Albedo.B"});
  di.albedo_odd = interleave(ch, {"odd.Albedo.R", "odd.Albedo.G", "odd.Albedo.B"});
  di.normal_even = interleave(ch, {"even.N.X", "even.N.Y", "even.N.Z"});
  di.normal_odd = interleave(ch, {"odd.N.X", "odd.N.Y", "odd.N.Z"});
  di.depth = ch.at("Z");
  di.samples = ch.at("spp");
  return di;
}

TEST(DenoiseCli, RoundTripWritesDenoisedNoisyAndCarriesEverythingOver) {
  const std::string dir = test::make_temp_dir("denoise-roundtrip");
  Channels ch = synthetic_frame();
  const std::string in = dir + "/in.exr", out = dir + "/out.exr", preview = dir + "/out.png";
  write_exr(in, ch);
  const auto r = tessera("denoise '" + in + "' -o '" + out + "' --preview '" + preview + "' -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_TRUE(fs::exists(preview));
  Imf::Header header;
  const Channels got = read_exr(out, &header);

  // The denoised RGB is the library's, bit for bit, on the same buffers (it is deterministic);
  // a file that names no sampler is taken as the default sampler's.
  EXPECT_EQ(interleave(got, {"R", "G", "B"}), denoise(library_input(ch), {}).rgb);
  EXPECT_EQ(got.at("A"), std::vector<float>(kW * kH, 1.0f));

  // The beauty became noisy.*, and every other channel is as it was.
  for (const char* c : {"R", "G", "B"}) EXPECT_EQ(got.at(std::string("noisy.") + c), ch.at(c)) << c;
  for (const auto& [name, values] : ch)
    if (name != "R" && name != "G" && name != "B") {
      EXPECT_EQ(got.at(name), values) << name;
    }
  EXPECT_EQ(header.typedAttribute<Imf::IntAttribute>("samplesPerPixel").value(), 8);
  EXPECT_EQ(header.typedAttribute<Imf::StringAttribute>("scene").value(), "synthetic");
}

// Halves from the independent sampler are independent: the header's `sampler` turns off the
// correction for the Sobol sampler's anticorrelated halves (DenoiseParams::half_variance_bias),
// which changes the result.
TEST(DenoiseCli, IndependentSamplersHalvesAreNotCorrected) {
  const std::string dir = test::make_temp_dir("denoise-independent");
  Channels ch = synthetic_frame();
  write_exr(dir + "/in.exr", ch, "independent");
  ASSERT_EQ(tessera("denoise '" + dir + "/in.exr' -o '" + dir + "/out.exr' -q").exit_code, 0);
  DenoiseParams independent;
  independent.half_variance_bias = 1.0f;
  const std::vector<float> got = interleave(read_exr(dir + "/out.exr"), {"R", "G", "B"});
  EXPECT_EQ(got, denoise(library_input(ch), independent).rgb);
  EXPECT_NE(got, denoise(library_input(ch), {}).rgb);
}

// The preview takes the display options render takes: its pixels are the denoised EXR's
// through the chosen view and exposure, exactly (to_display_rgb8), and the default (filmic)
// looks otherwise. Given without --preview they warn; a bad OCIO config fails before any work.
std::vector<std::uint8_t> png_rgb(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  const OIIO::ImageSpec spec = in->spec();
  std::vector<std::uint8_t> px(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels);
  in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, px.data());
  std::vector<std::uint8_t> rgb;
  for (std::size_t i = 0; i < px.size(); i += spec.nchannels) rgb.insert(rgb.end(), &px[i], &px[i] + 3);
  return rgb;
}

TEST(DenoiseCli, PreviewTakesTheViewAndExposure) {
  const std::string dir = test::make_temp_dir("denoise-preview");
  Channels ch = synthetic_frame();
  const std::string in = dir + "/in.exr";
  write_exr(in, ch);
  auto r = tessera("denoise '" + in + "' -o '" + dir + "/out.exr' --preview '" + dir +
                   "/standard.png' --view-transform standard --exposure 1 -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<float> denoised = interleave(read_exr(dir + "/out.exr"), {"R", "G", "B"});
  EXPECT_EQ(png_rgb(dir + "/standard.png"), to_display_rgb8(denoised, 1.0f, {ViewTransform::standard}));
  ASSERT_EQ(tessera("denoise '" + in + "' -o '" + dir + "/out2.exr' --preview '" + dir + "/filmic.png' -q").exit_code, 0);
  EXPECT_EQ(png_rgb(dir + "/filmic.png"), to_display_rgb8(denoised, 0.0f, {ViewTransform::filmic}));
  EXPECT_NE(png_rgb(dir + "/filmic.png"), png_rgb(dir + "/standard.png"));

  r = tessera("denoise '" + in + "' -o '" + dir + "/out3.exr' --exposure 1 -q");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.err, "tessera: warning: --exposure: applies to --preview, which is not given\n");
  const std::string config = dir + "/broken.ocio";
  std::ofstream(config) << "not an OCIO config\n";
  r = tessera("denoise '" + in + "' -o '" + dir + "/out4.exr' --preview '" + dir + "/p.png' --ocio-config '" + config + "'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(config), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/out4.exr"));
}

// `render --denoise` and `tessera denoise` on a render with the same buffers are one
// operation: the same denoised bits, and the noisy beauty is the plain render's, bit for bit
// (denoising adds layers, it never changes the samples).
TEST(DenoiseCli, RenderDenoiseEqualsDenoisingTheRenderedFile) {
  const std::string dir = test::make_temp_dir("denoise-render");
  const std::string scene = test::scene_path("cornell-box/cornell-box.gltf");
  for (const char* sampler : {"sobol", "independent"}) {
  SCOPED_TRACE(sampler);
  const std::string common = fmt::format(" --width {} --height {} --spp 8 --seed 3 -q --sampler {}", kW, kH, sampler);
  ASSERT_EQ(tessera("render '" + scene + "' -o '" + dir + "/plain.exr'" + common).exit_code, 0);
  ASSERT_EQ(tessera("render '" + scene + "' -o '" + dir + "/buffers.exr' --aov halves,albedo,normal" + common).exit_code, 0);
  const auto r = tessera("render '" + scene + "' -o '" + dir + "/denoised.exr' --denoise" + common);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_EQ(tessera("denoise '" + dir + "/buffers.exr' -o '" + dir + "/afterwards.exr' -q").exit_code, 0);
  Imf::Header header;
  const Channels denoised = read_exr(dir + "/denoised.exr", &header), afterwards = read_exr(dir + "/afterwards.exr");
  const Channels plain = read_exr(dir + "/plain.exr");
  for (const char* c : {"R", "G", "B"}) {
    EXPECT_EQ(denoised.at(c), afterwards.at(c)) << c;
    EXPECT_EQ(denoised.at(std::string("noisy.") + c), plain.at(c)) << c;
    EXPECT_NE(denoised.at(c), plain.at(c)) << c;
    for (float v : denoised.at(c)) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f);
  }
  EXPECT_EQ(header.typedAttribute<Imf::IntAttribute>("denoised").value(), 1);
  for (const char* c : {"even.R", "odd.R", "Albedo.G", "N.Z", "spp"}) EXPECT_EQ(denoised.count(c), 1u) << c;
  }
}

}  // namespace
}  // namespace tessera
