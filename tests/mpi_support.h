// Running tessera under a real `mpirun` (Open MPI) from the tests: the MPI tests' shared
// command lines. Header only: included by the MPI tests alone.
#pragma once

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

#include "tests/exr_read.h"
#include "tests/test_support.h"

namespace tessera::test {

inline std::string quote(const std::string& s) { return "'" + s + "'"; }

inline bool have_mpirun() { return std::system("command -v mpirun > /dev/null 2>&1") == 0; }

// Open MPI refuses root without --allow-run-as-root (CI runs as root); --bind-to none lets
// each rank's TBB threads use every core. Leak checking is off for the ranks: a sanitizer
// build would report Open MPI's own allocations, which it keeps until exit. A job still
// running after `seconds` is stopped (mpirun, told to stop, kills its ranks): exit code 124.
inline std::string mpirun(int ranks, int seconds = 300) {
  return "env ASAN_OPTIONS=detect_leaks=0 timeout " + std::to_string(seconds) + " mpirun --oversubscribe --bind-to none " +
         std::string(geteuid() == 0 ? "--allow-run-as-root " : "") + "-np " + std::to_string(ranks) + " ";
}

// tessera render of the Cornell box, 40x36, seed 9, to `out`, with `extra` options.
inline std::string render_args(const std::string& out, const std::string& extra) {
  return quote(tessera_exe()) + " render " + quote(scene_path("cornell-box/cornell-box.gltf")) +
         " --width 40 --height 36 --seed 9 -o " + quote(out) + " " + extra;
}

inline void expect_same_pixels(const std::string& a, const std::string& b) {
  EXPECT_EQ(exr_rgb(a), exr_rgb(b)) << a << " and " << b << " differ";
}

// A shell script that starts the job in `$@` in the background, waits for its output file
// `$1` (a first checkpoint), runs `action` (shell, on the process "$p") on the processes whose
// environment matches `which` (e.g. OMPI_COMM_WORLD_RANK=1; empty: mpirun itself), waits
// for the job, and prints "rc=CODE ms=MILLISECONDS" (from the action's end to the job's).
inline std::string job_script(const std::string& which, const std::string& action) {
  return "out=$1; shift\n"
         "\"$@\" > /dev/null 2> \"$out.log\" &\n"
         "job=$!\n"
         "for i in $(seq 1 3000); do [ -f \"$out\" ] && break; sleep 0.01; done\n"
         "for p in $(pgrep -f -- \"$out\"); do\n" +
         (which.empty() ? std::string("  if [ \"$(cat /proc/$p/comm)\" = mpirun ]; then\n")
                        : "  if grep -qa \"" + which + "\" \"/proc/$p/environ\" 2>/dev/null; then\n") +
         "    " + action + "\n"
         "    acted=\"$acted $p\"\n"
         "  fi\n"
         "done\n"
         "t0=$(date +%s%N)\n"
         "wait $job; rc=$?\n"
         "for p in $acted; do kill -9 \"$p\" 2> /dev/null; done  # none should be left\n"
         "echo \"rc=$rc ms=$(( ($(date +%s%N) - t0) / 1000000 ))\"\n";
}

// job_script sending SIGNAL.
inline std::string signal_script(const std::string& signal, const std::string& which) {
  return job_script(which, "kill -" + signal + " \"$p\"");
}

// A job run under job_script: its exit code, the milliseconds from the action (a signal) to
// its end, and its standard error.
struct SignalledJob {
  int rc = -1, ms = -1;
  std::string log;
};

inline SignalledJob run_script(const std::string& out, const std::string& script_text, const std::string& job) {
  const std::string script = out + ".sh";
  {
    std::ofstream(script) << script_text;
  }
  const CommandResult r = run_command("bash " + quote(script) + " " + quote(out) + " " + job);
  SignalledJob j;
  std::sscanf(r.out.c_str(), "rc=%d ms=%d", &j.rc, &j.ms);
  std::ifstream in(out + ".log");
  j.log.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return j;
}

inline SignalledJob run_signalled(const std::string& out, const std::string& signal, const std::string& which,
                                  const std::string& job) {
  return run_script(out, signal_script(signal, which), job);
}

// The partial frame `out`, resumed in one process, is the uninterrupted render's, bit for bit.
inline void expect_resumes_to_whole(const std::string& out, const std::string& opts) {
  ASSERT_EQ(exr_int(out, "partial"), 1) << "no partial frame before the signal: nothing to test";
  const CommandResult resumed = run_command(render_args(out, opts + " --resume " + quote(out)));
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  const std::string whole = out + ".whole.exr";
  ASSERT_EQ(run_command(render_args(whole, opts)).exit_code, 0);
  expect_same_pixels(whole, out);
}

class MpiTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!have_mpirun()) GTEST_SKIP() << "mpirun not found (apt-get install openmpi-bin)";
  }
};

}  // namespace tessera::test
