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

// glibc (2.35 and later) backs malloc's large blocks with transparent huge pages when the
// tunable glibc.malloc.hugetlb=1 is set, read only as a process starts: the hand-over sets it
// for the program it starts (one started directly, as under valgrind, keeps 4 KiB pages). A
// render reads its meshes, textures and BVH at random, and with 4 KiB pages most of those
// reads also miss the TLB: DamagedHelmet and MetalRoughSpheresNoTextures render 3-5% faster
// (docs/performance.md). The variable `tunables` with that added; one that names the tunable
// already (glibc.malloc.hugetlb=0, say) is kept as it is.
std::string tunables_with_huge_pages(const std::string& tunables);
// Whether this process started with malloc asked for huge pages.
bool malloc_asks_for_huge_pages();

// The program built for `isa`, in the same directory as this one.
std::string program_for_isa(const std::string& isa);

// Returns -1 to go on in this process, or the exit code after a message (a bad TESSERA_ISA,
// an instruction set this CPU lacks or this build has not). Does not return after a hand-over.
int run_chosen_isa(char** argv);

}  // namespace tessera
