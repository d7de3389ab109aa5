// The EXR as compositors expect it (issue 15): float Z and N under --half, +infinity depth
// where nothing was hit, the standard attributes (capDate, utcOffset, chromaticities, owner,
// comments) and the command line, the resume data out of the first part's layer list, and
// `--resume FILE` alone continuing with the options the file stores.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <limits>
#include <map>
#include <regex>

#include "tests/exr_read.h"
#include "tests/test_support.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;

std::string quote(const std::string& s) { return "'" + s + "'"; }

test::CommandResult tessera(const std::string& args) {
  return test::run_command("timeout 300 " + quote(test::tessera_exe()) + " " + args);
}

std::string cornell() { return test::scene_path("cornell-box/cornell-box.gltf"); }
// A box in front of the background, so that some camera rays miss.
std::string open_scene() { return test::scene_path("material-variants/material-variants.gltf"); }

// Subimage `part` of an EXR as OpenImageIO (and so Nuke, Blender, oiiotool) lists it.
struct Part {
  OIIO::ImageSpec spec;
  std::map<std::string, std::vector<float>> channels;  // every channel, read as float
};

Part read_part(const std::string& path, int part = 0) {
  auto in = OIIO::ImageInput::open(path);
  EXPECT_TRUE(in) << path << ": " << OIIO::geterror();
  Part p;
  if (!in || !in->seek_subimage(part, 0)) return p;
  p.spec = in->spec();
  const std::size_t n = static_cast<std::size_t>(p.spec.width) * p.spec.height;
  std::vector<float> all(n * p.spec.nchannels);
  EXPECT_TRUE(in->read_image(part, 0, 0, p.spec.nchannels, OIIO::TypeDesc::FLOAT, all.data()));
  for (int c = 0; c < p.spec.nchannels; ++c) {
    std::vector<float>& ch = p.channels[p.spec.channelnames[c]];
    for (std::size_t i = 0; i < n; ++i) ch.push_back(all[i * p.spec.nchannels + c]);
  }
  return p;
}

int subimages(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  int n = 0;
  while (in && in->seek_subimage(n, 0)) ++n;
  return n;
}

bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

TEST(ExrConventions, HalfAppliesToColourChannelsOnly) {
  const std::string out = test::make_temp_dir("exr-half") + "/half.exr";
  const auto r = tessera("render " + quote(cornell()) + " -o " + quote(out) +
                         " --width 16 --spp 2 -q --half --aov albedo,normal,depth,halves,cost");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Part p = read_part(out);
  ASSERT_GT(p.spec.nchannels, 10);
  for (int c = 0; c < p.spec.nchannels; ++c) {
    const std::string name = p.spec.channelnames[c];
    const std::string last = name.substr(name.rfind('.') + 1);
    const bool variance = name.rfind("variance.", 0) == 0;  // half would overflow a firefly's
    const bool colour = !variance && (last == "R" || last == "G" || last == "B" || last == "A");
    EXPECT_EQ(p.spec.channelformat(c), colour ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT) << name;
  }
  for (const char* name : {"R", "A", "Albedo.G", "even.B", "Z", "N.X", "even.N.Y", "variance.G", "spp", "cost.time"})
    EXPECT_TRUE(p.channels.count(name)) << name;
}

TEST(ExrConventions, DepthIsInfiniteWhereNothingWasHit) {
  const std::string out = test::make_temp_dir("exr-depth") + "/z.exr";
  const auto r = tessera("render " + quote(open_scene()) + " -o " + quote(out) + " --width 32 --spp 4 -q --aov depth "
                         "--film-transparent");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Part p = read_part(out);
  const std::vector<float>&z = p.channels.at("Z"), &a = p.channels.at("A");
  int misses = 0, hits = 0;
  for (std::size_t i = 0; i < z.size(); ++i) {
    if (a[i] == 0.0f) {  // no camera ray of the pixel hit anything
      EXPECT_EQ(z[i], std::numeric_limits<float>::infinity()) << i;
      ++misses;
    } else {
      EXPECT_TRUE(std::isfinite(z[i]) && z[i] > 0.0f) << i << ": " << z[i];
      ++hits;
    }
  }
  EXPECT_GT(misses, 0);
  EXPECT_GT(hits, 0);
}

TEST(ExrConventions, TheHeaderHasTheStandardAttributesAndTheCommandLine) {
  const std::string dir = test::make_temp_dir("exr-metadata");
  const std::string args = "render " + quote(cornell()) + " -o " + quote(dir + "/m.exr") +
                           " --width 8 --spp 1 -q --owner 'Studio X' --comments \"shot 12, it's take 3\"";
  const std::time_t before = std::time(nullptr);
  const auto r = tessera(args);
  const std::time_t after = std::time(nullptr);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto in = OIIO::ImageInput::open(dir + "/m.exr");
  ASSERT_TRUE(in);
  const OIIO::ImageSpec& spec = in->spec();
  // OpenImageIO's names for OpenEXR's standard owner, comments and capDate.
  EXPECT_EQ(spec.get_string_attribute("Copyright"), "Studio X");
  EXPECT_EQ(spec.get_string_attribute("ImageDescription"), "shot 12, it's take 3");
  const std::string cap_date = spec.get_string_attribute("DateTime");
  ASSERT_TRUE(std::regex_match(cap_date, std::regex(R"(\d{4}:\d{2}:\d{2} \d{2}:\d{2}:\d{2})"))) << cap_date;
  std::tm tm{};
  ASSERT_NE(strptime(cap_date.c_str(), "%Y:%m:%d %H:%M:%S", &tm), nullptr);
  tm.tm_isdst = -1;
  const std::time_t captured = std::mktime(&tm);  // local time, as capDate is
  EXPECT_GE(captured, before - 1);
  EXPECT_LE(captured, after + 1);
  std::tm local{};
  localtime_r(&before, &local);
  EXPECT_EQ(spec.get_float_attribute("utcOffset", 1e9f), static_cast<float>(-local.tm_gmtoff));
  // Rec.709 primaries and the D65 white point.
  const OIIO::ParamValue* chroma = spec.find_attribute("chromaticities");
  ASSERT_TRUE(chroma);
  ASSERT_EQ(chroma->type().numelements() * chroma->type().aggregate, 8u);
  const float* xy = static_cast<const float*>(chroma->data());
  const float expected[8] = {0.64f, 0.33f, 0.30f, 0.60f, 0.15f, 0.06f, 0.3127f, 0.3290f};
  for (int i = 0; i < 8; ++i) EXPECT_FLOAT_EQ(xy[i], expected[i]) << i;
  // The command as run, each argument quoted where a shell needs it.
  EXPECT_EQ(spec.get_string_attribute("tesseraCommandLine"),
            test::tessera_exe() + " render " + cornell() + " -o " + dir + "/m.exr --width 8 --spp 1 -q --owner "
            "'Studio X' --comments 'shot 12, it'\\''s take 3'");
  // Neither owner nor comments when not given.
  ASSERT_EQ(tessera("render " + quote(cornell()) + " -o " + quote(dir + "/n.exr") + " --width 8 --spp 1 -q").exit_code, 0);
  auto plain = OIIO::ImageInput::open(dir + "/n.exr");
  EXPECT_FALSE(plain->spec().find_attribute("Copyright"));
  EXPECT_FALSE(plain->spec().find_attribute("ImageDescription"));
}

const std::string kSettings = " --width 40 --spp 40 --max-bounces 4 --seed 7 --pixel-filter gaussian --aov depth "
                              "--film-transparent -q";

// A partial frame lists only the frame's own channels in its first part, as compositors
// open it; the resume data is the second part. --resume alone still continues it exactly.
TEST(ExrConventions, APartialHidesItsResumeDataAndResumeAloneFinishesIt) {
  const std::string dir = test::make_temp_dir("exr-partial");
  ASSERT_EQ(tessera("render " + quote(open_scene()) + " -o " + quote(dir + "/whole.exr") + kSettings).exit_code, 0);
  auto r = tessera("render " + quote(open_scene()) + " -o " + quote(dir + "/part.exr") + kSettings + " --time-limit 0.001");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_EQ(test::exr_int(dir + "/part.exr", "partial"), 1);
  EXPECT_EQ(read_part(dir + "/part.exr").spec.channelnames, (std::vector<std::string>{"R", "G", "B", "A", "Z"}));
  ASSERT_EQ(subimages(dir + "/part.exr"), 2);
  const Part resume_part = read_part(dir + "/part.exr", 1);
  EXPECT_EQ(resume_part.spec.get_string_attribute("name"), "tessera.resume");
  EXPECT_TRUE(resume_part.channels.count("tessera.samples"));

  // Another directory, nothing but --resume: the scene, size, spp, seed, filter and AOVs
  // are the file's.
  r = test::run_command("cd " + quote(test::make_temp_dir("exr-partial-elsewhere")) + " && " +
                        quote(test::tessera_exe()) + " render --resume " + quote(dir + "/part.exr") + " -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(test::exr_int(dir + "/part.exr", "partial"), 0);
  EXPECT_EQ(subimages(dir + "/part.exr"), 1);  // finished: a plain frame
  const Part whole = read_part(dir + "/whole.exr"), resumed = read_part(dir + "/part.exr");
  for (const char* name : {"R", "G", "B", "A", "Z"})
    EXPECT_TRUE(same_bits(whole.channels.at(name), resumed.channels.at(name))) << name;
}

TEST(ExrConventions, ResumeRefusesAContradictingOptionByName) {
  const std::string dir = test::make_temp_dir("exr-resume-contradiction");
  const std::string part = dir + "/part.exr";
  ASSERT_EQ(tessera("render " + quote(cornell()) + " -o " + quote(part) + kSettings + " --time-limit 0.001").exit_code, 0);
  const auto before = fs::last_write_time(part);
  const auto r = tessera("render --resume " + quote(part) + " --width 64");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "tessera: error: --resume " + part + ": --width 64 contradicts the file, rendered with --width 40; "
                   "leave it out to continue as it was started\n");
  EXPECT_EQ(fs::last_write_time(part), before);
  // The same option with the file's value is no contradiction.
  EXPECT_EQ(tessera("render --resume " + quote(part) + " --width 40 --time-limit 0.001 -q").exit_code, 0);
}

}  // namespace
}  // namespace tessera
