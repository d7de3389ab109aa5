// tessera and tessera-x86-64-v3 (app/isa_dispatch.h): which one runs, and that both make the
// same image bit for bit. Which instruction sets the CPU has is read here from the CPUID bits
// themselves, independently of the program's own check (__builtin_cpu_supports). Not from
// /proc/cpuinfo: some virtual machines' kernels leave flags out of it that CPUID reports (an
// AMD EPYC guest listed no abm, LZCNT, while running x86-64-v3 code correctly).
#include <gtest/gtest.h>

#include <cpuid.h>

#include <filesystem>
#include <string>

#include "imageio/image_input.h"
#include "tests/exr_read.h"
#include "tests/same_bits.h"
#include "tests/test_support.h"

namespace tessera {
namespace {

std::string quote(const std::string& s) { return "'" + s + "'"; }

// x86-64-v3's features beyond v2 (AVX, AVX2, BMI1, BMI2, F16C, FMA, LZCNT, MOVBE), and the
// operating system saving the AVX registers (OSXSAVE, and XCR0's SSE and AVX state bits).
bool cpu_has_x86_64_v3() {
  unsigned a, b, c, d;
  if (!__get_cpuid(1, &a, &b, &c, &d)) return false;
  const bool leaf1 = (c & bit_AVX) && (c & bit_FMA) && (c & bit_F16C) && (c & bit_MOVBE) && (c & bit_OSXSAVE);
  if (!leaf1 || !__get_cpuid_count(7, 0, &a, &b, &c, &d)) return false;
  const bool leaf7 = (b & bit_AVX2) && (b & bit_BMI) && (b & bit_BMI2);
  if (!leaf7 || !__get_cpuid(0x80000001, &a, &b, &c, &d) || !(c & bit_LZCNT)) return false;
  unsigned xcr0_low, xcr0_high;
  __asm__("xgetbv" : "=a"(xcr0_low), "=d"(xcr0_high) : "c"(0));
  return (xcr0_low & 6u) == 6u;
}

std::string v3_program() {
  return (std::filesystem::path(test::tessera_exe()).parent_path() / "tessera-x86-64-v3").string();
}

bool v3_runs_here() { return std::filesystem::exists(v3_program()) && cpu_has_x86_64_v3(); }

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
  if (cpu_has_x86_64_v3()) GTEST_SKIP() << "this CPU runs x86-64-v3";
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
