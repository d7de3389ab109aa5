// tessera is built once per instruction set: `tessera` for any x86-64 CPU and, beside it,
// `tessera-x86-64-v3` for CPUs with AVX2, FMA and BMI2 (renderer/CMakeLists.txt). Both make the
// same image bit for bit; the second is faster. At start, the program hands over (execv: same
// process, arguments and environment) to the one the environment variable TESSERA_ISA asks for:
//   auto (or unset)  the fastest the CPU runs and the build has
//   x86-64           the generic program
//   x86-64-v3        the AVX2/FMA program; an error on a CPU without them
#pragma once

#include <string>

namespace tessera {

// Does this CPU (and its operating system, for the AVX registers) run x86-64-v3 code?
bool cpu_runs_x86_64_v3();

// The program built for `isa`, in the same directory as this one.
std::string program_for_isa(const std::string& isa);

// Returns -1 to go on in this process, or the exit code after a message (a bad TESSERA_ISA,
// an instruction set this CPU lacks or this build has not). Does not return after a hand-over.
int run_chosen_isa(char** argv);

}  // namespace tessera
