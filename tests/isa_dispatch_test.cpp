// tessera and tessera-x86-64-v3 (app/isa_dispatch.h): which one runs, and that both make the
// same image bit for bit. Which instruction sets the CPU has is read here from /proc/cpuinfo,
// independently of the program's own check (__builtin_cpu_supports).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "renderer/image_input.h"
#include "tests/exr_read.h"
#include "tests/same_bits.h"
#include "tests/test_support.h"

namespace tessera {
namespace {

std::string quote(const std::string& s) { return "'" + s + "'"; }

// x86-64-v3's flags beyond v2 as /proc/cpuinfo names them (abm: lzcnt). The kernel lists avx only
// when it saves the AVX registers.
bool cpuinfo_has_x86_64_v3() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("flags", 0) != 0) continue;
    std::istringstream words(line.substr(line.find(':') + 1));
    std::set<std::string> flags;
    for (std::string w; words >> w;) flags.insert(w);
    for (const char* f : {"avx", "avx2", "bmi1", "bmi2", "f16c", "fma", "abm", "movbe", "xsave"})
      if (!flags.count(f)) return false;
    return true;
  }
  return false;
}

std::string v3_program() {
  return (std::filesystem::path(test::tessera_exe()).parent_path() / "tessera-x86-64-v3").string();
}

bool v3_runs_here() { return std::filesystem::exists(v3_program()) && cpuinfo_has_x86_64_v3(); }

test::CommandResult tessera_with_isa(const std::string& isa, const std::string& args) {
  const std::string env = isa.empty() ? "env -u TESSERA_ISA " : "env TESSERA_ISA=" + quote(isa) + " ";
  return test::run_command(env + "timeout 300 " + quote(test::tessera_exe()) + " " + args);
}

TEST(IsaDispatch, VersionNamesTheProgramThatRuns) {
  const auto automatic = tessera_with_isa("", "--version");
  ASSERT_EQ(automatic.exit_code, 0) << automatic.err;
  const std::string fastest = v3_runs_here() ? "x86-64-v3" : "x86-64";
  EXPECT_NE(automatic.out.find("(" + fastest + ")\n"), std::string::npos) << automatic.out;
  EXPECT_EQ(tessera_with_isa("auto", "--version").out, automatic.out);
  const auto generic = tessera_with_isa("x86-64", "--version");
  ASSERT_EQ(generic.exit_code, 0) << generic.err;
  EXPECT_NE(generic.out.find("(x86-64)\n"), std::string::npos) << generic.out;
}

TEST(IsaDispatch, TheGenericProgramIsReachedFromTheOther) {
  if (!v3_runs_here()) GTEST_SKIP() << "no x86-64-v3 program or CPU here";
  const auto r = test::run_command("env TESSERA_ISA=x86-64 " + quote(v3_program()) + " --version");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("(x86-64)\n"), std::string::npos) << r.out;
}

TEST(IsaDispatch, AnUnknownInstructionSetIsNamed) {
  const auto r = tessera_with_isa("avx9", "--version");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err, "tessera: error: TESSERA_ISA=avx9: expected auto, x86-64 or x86-64-v3\n");
}

TEST(IsaDispatch, AskingForX8664V3WithoutItIsAnError) {
  if (cpuinfo_has_x86_64_v3()) GTEST_SKIP() << "this CPU runs x86-64-v3";
  const auto r = tessera_with_isa("x86-64-v3", "--version");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("lacks AVX2"), std::string::npos) << r.err;
}

// Renders `args` with each program: every layer the same bit for bit, each file naming its program.
void expect_same_render(const std::string& name, const std::string& args) {
  const std::string dir = test::make_temp_dir("isa-" + name);
  const std::string generic = dir + "/generic.exr", v3 = dir + "/v3.exr";
  const auto a = tessera_with_isa("x86-64", "render " + args + " -q -o " + quote(generic));
  ASSERT_EQ(a.exit_code, 0) << a.err;
  const auto b = tessera_with_isa("x86-64-v3", "render " + args + " -q -o " + quote(v3));
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_EQ(test::exr_string(generic, "tesseraIsa"), "x86-64");
  EXPECT_EQ(test::exr_string(v3, "tesseraIsa"), "x86-64-v3");
  SCOPED_TRACE(name);
  test::expect_same_image(read_frame_exr(generic), read_frame_exr(v3));
}

// Scenes that between them run every material lobe, textures, lights, the environment, the
// lens, motion blur, the features and the denoiser.
TEST(IsaDispatch, BothProgramsMakeTheSameImage) {
  if (!v3_runs_here()) GTEST_SKIP() << "no x86-64-v3 program or CPU here";
  const std::string size = " --width 48 --height 36 --spp 8 --threads 2";
  expect_same_render("cornell", quote(test::scene_path("cornell-box/cornell-box.gltf")) + size +
                                    " --aov albedo,normal,depth,halves --denoise");
  expect_same_render("helmet", quote(test::scene_path("khronos/DamagedHelmet/glTF-Binary/DamagedHelmet.glb")) +
                                   size + " --envmap " + quote(test::scene_path("env/spruit_sunrise_1k.hdr")) +
                                   " --aperture 0.05");
  expect_same_render("spheres",
                     quote(test::scene_path(
                         "khronos/MetalRoughSpheresNoTextures/glTF-Binary/MetalRoughSpheresNoTextures.glb")) +
                         size);
  for (const char* scene : {"material-extensions/iridescence.gltf", "material-extensions/dispersion.gltf",
                            "material-extensions/diffuse-transmission.gltf",
                            "khronos/ClearCoatTest/glTF-Binary/ClearCoatTest.glb",
                            "khronos/TransmissionRoughnessTest/glTF-Binary/TransmissionRoughnessTest.glb",
                            "khronos/AnisotropyRotationTest/glTF-Binary/AnisotropyRotationTest.glb"})
    expect_same_render(test::identifier(scene), quote(test::scene_path(scene)) + size);
  expect_same_render("motion", quote(test::scene_path("khronos/BoxAnimated/glTF-Binary/BoxAnimated.glb")) + size +
                                   " --frame 12 --shutter -0.5,0.5");
}

}  // namespace
}  // namespace tessera
