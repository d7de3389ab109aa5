// The instruction set this build of the renderer was compiled for. renderer/CMakeLists.txt
// builds it once for generic x86-64 and once for x86-64-v3 (AVX2, FMA, BMI2); app/isa_dispatch.h
// runs the program linked with the one the CPU can execute.
#pragma once

#include <string_view>

namespace tessera {

// "x86-64", "x86-64-v3" (or the processor's name on other architectures).
std::string_view compiled_isa();

}  // namespace tessera
