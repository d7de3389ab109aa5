#include "app/isa_dispatch.h"

#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string_view>

#include <fmt/format.h>

#include "app/cli/exit_codes.h"
#include "renderer/util/isa.h"

namespace tessera {
namespace {

constexpr std::string_view kGeneric = "x86-64";
constexpr std::string_view kV3 = "x86-64-v3";

int isa_error(const std::string& message) {
  fmt::print(stderr, "tessera: error: {}\n", message);
  return kExitBadInput;
}

// The program built for x86-64-v3 must not run a single AVX instruction on a CPU without it,
// not even in a static initialiser: checked before them all.
__attribute__((constructor(101))) void refuse_missing_isa() {
  if (compiled_isa() != kV3 || cpu_runs_x86_64_v3()) return;
  std::_Exit(isa_error(fmt::format("this program is built for x86-64-v3 (AVX2, FMA, BMI2), which this CPU lacks: "
                                   "run {} instead",
                                   program_for_isa(std::string(kGeneric)))));
}

}  // namespace

bool cpu_runs_x86_64_v3() {
#if !defined(__x86_64__)
  return false;
#else
  __builtin_cpu_init();
#if defined(__clang__)  // clang 14 knows no level names; these are the features that matter here
  return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi") &&
         __builtin_cpu_supports("bmi2");
#else
  return __builtin_cpu_supports("x86-64-v3");
#endif
#endif
}

std::string program_for_isa(const std::string& isa) {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  const std::string name = isa == kGeneric ? "tessera" : "tessera-" + isa;
  return ec ? name : (self.parent_path() / name).string();
}

int run_chosen_isa(char** argv) {
  const char* variable = std::getenv("TESSERA_ISA");
  std::string wanted = variable && *variable ? variable : "auto";
  if (wanted != "auto" && wanted != kGeneric && wanted != kV3)
    return isa_error(fmt::format("TESSERA_ISA={}: expected auto, {} or {}", wanted, kGeneric, kV3));
  const std::string_view mine = compiled_isa();
  if (wanted == "auto") {  // the faster program when the CPU runs it and the build made it
    if (mine != kGeneric || !cpu_runs_x86_64_v3() || access(program_for_isa(std::string(kV3)).c_str(), X_OK) != 0)
      return -1;
    wanted = kV3;
  }
  if (wanted == mine) return -1;
  if (wanted == kV3 && !cpu_runs_x86_64_v3())
    return isa_error("TESSERA_ISA=x86-64-v3, but this CPU lacks AVX2, FMA or BMI2");
  const std::string program = program_for_isa(wanted);
  execv(program.c_str(), argv);
  return isa_error(fmt::format("TESSERA_ISA={}: cannot run {}: {}", wanted, program, std::strerror(errno)));
}

}  // namespace tessera
