// Profiling and faults of a distributed render, with a real `mpirun`: --stats-json, --trace
// and the heat map describe every rank; the dynamic counter balances the ranks where static
// blocks do not; a time limit, a stopped (hung) rank and a signal end the job as documented in
// docs/distributed.md, leaving a frame that resumes to the uninterrupted bits.
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/mpi_support.h"

namespace tessera {
namespace {

using nlohmann::json;
using test::expect_same_pixels;
using test::mpirun;
using test::quote;
using test::render_args;

using MpiProfile = test::MpiTest;
using MpiFaults = test::MpiTest;

json read_json(const std::string& path) {
  std::ifstream in(path);
  return json::parse(in);
}

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST_F(MpiProfile, StatsJsonAndTraceDescribeEveryRank) {
  const std::string dir = test::make_temp_dir("mpi-profile");
  const auto r = test::run_command(mpirun(3) + render_args(dir + "/f.exr", "--spp 16 --tile-size 8 --threads 1 --stats-json " +
                                                                             quote(dir + "/s.json") + " --trace " +
                                                                             quote(dir + "/t.json") + " --heatmap " +
                                                                             quote(dir + "/h.svg") + " --heatmap-by rank"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("3 ranks: cluster efficiency"), std::string::npos) << r.err;
  const json s = read_json(dir + "/s.json");
  EXPECT_EQ(s["frame"]["ranks"], 3);
  ASSERT_EQ(s["per_rank"].size(), 3u);
  ASSERT_EQ(s["per_thread"].size(), 3u);  // one thread on each rank
  // Every tile of every wave ran once, on one rank; their samples are the frame's.
  std::map<int, double> busy;
  std::set<std::pair<int, int>> ran;
  std::uint64_t samples = 0;
  for (const json& run : s["tile_runs"]) {
    EXPECT_TRUE(ran.insert({run["wave"].get<int>(), run["tile"].get<int>()}).second) << "a tile ran twice in a wave";
    busy[run["rank"]] += run["end"].get<double>() - run["start"].get<double>();
    samples += run["samples"].get<std::uint64_t>();
  }
  EXPECT_EQ(ran.size(), s["waves"].size() * s["tiles"].size());
  EXPECT_EQ(samples, 40u * 36u * 16u);
  EXPECT_EQ(s["frame"]["camera_samples"], 40 * 36 * 16);
  // Each rank's busy time is its tile runs' time; the cluster's efficiency follows from them.
  double busy_sum = 0.0;
  for (const json& rank : s["per_rank"]) {
    const int k = rank["rank"];
    EXPECT_NEAR(rank["busy_seconds"].get<double>(), busy[k], 1e-6) << "rank " << k;
    EXPECT_GT(rank["communication_seconds"].get<double>(), 0.0) << "rank " << k;
    EXPECT_LT(rank["communication_seconds"].get<double>(), s["frame"]["render_seconds"].get<double>());
    EXPECT_NEAR(rank["idle_seconds"].get<double>(), s["frame"]["wall_seconds"].get<double>() - busy[k], 1e-6);
    busy_sum += busy[k];
  }
  EXPECT_NEAR(s["frame"]["parallel_efficiency"].get<double>(), busy_sum / (3 * s["frame"]["wall_seconds"].get<double>()),
              1e-9);
  // The trace: a process per rank named "rank N", each tile run on its rank's process.
  const json t = read_json(dir + "/t.json");
  std::map<int, std::string> processes;
  std::size_t slices = 0;
  for (const json& e : t["traceEvents"]) {
    if (e["ph"] == "M" && e["name"] == "process_name") processes[e["pid"]] = e["args"]["name"];
    if (e["ph"] == "X") ++slices;
  }
  EXPECT_EQ(processes, (std::map<int, std::string>{{1, "rank 0"}, {2, "rank 1"}, {3, "rank 2"}}));
  EXPECT_EQ(slices, s["tile_runs"].size());
  for (const json& e : t["traceEvents"]) {
    if (e["ph"] == "X") {
      EXPECT_TRUE(busy.count(e["pid"].get<int>() - 1)) << "a slice on a rank with no runs";
    }
  }
  EXPECT_NE(slurp(dir + "/h.svg").find("</svg>"), std::string::npos);
}

// The paper's adversarial scene puts nearly all the work in one corner: static blocks give it
// to one rank, the counter shares it. Measured as the ranks' balance, mean over most: the
// cluster's efficiency were communication free. Static blocks fix each rank's tiles, so their
// CPU time is the split, whatever else ran on this shared machine. The counter gives tiles to
// whichever rank is free, so it evens out the ranks' busy time (time in tiles), which is what
// the frame waits for; a rank the machine's other processes slow down takes fewer tiles.
double rank_balance(const json& stats, const char* seconds) {
  double sum = 0.0, most = 0.0;
  for (const json& rank : stats["per_rank"]) {
    sum += rank[seconds].get<double>();
    most = std::max(most, rank[seconds].get<double>());
  }
  return sum / (stats["per_rank"].size() * most);
}

TEST_F(MpiProfile, TheCounterBalancesTheRanksWhereStaticBlocksDoNot) {
  const std::string dir = test::make_temp_dir("mpi-balance");
  std::map<std::string, json> stats;
  for (const std::string scheduler : {"dynamic", "static"}) {
    const std::string file = dir + "/" + scheduler + ".json";
    const auto r = test::run_command(mpirun(2) + quote(test::tessera_exe()) + " render " +
                                     quote(test::scene_path("paper/adversarial.gltf")) +
                                     " -q --width 96 --spp 64 --threads 1 --tile-size 8 --rank-scheduler " + scheduler +
                                     " -o " + quote(dir + "/" + scheduler + ".exr") + " --stats-json " + quote(file));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    stats[scheduler] = read_json(file);
  }
  EXPECT_LT(rank_balance(stats["static"], "cpu_seconds"), 0.75) << "the corner did not fall to one rank";
  EXPECT_GT(rank_balance(stats["dynamic"], "busy_seconds"), 0.85);
}

// tessera scaling over ranks x threads: the runs of several ranks are `tessera render` under
// mpirun, read back from their statistics; a launcher that cannot run is one clear error.
TEST_F(MpiProfile, ScalingSweepsRanksAndThreads) {
  const std::string dir = test::make_temp_dir("mpi-scaling");
  // The ranks inherit the environment: no leak checking for Open MPI's own allocations, as
  // the other MPI tests' command lines do.
  const std::string scaling = "env ASAN_OPTIONS=detect_leaks=0 " + quote(test::tessera_exe()) + " scaling " +
                              quote(test::scene_path("cornell-box/cornell-box.gltf")) +
                              " -q --threads-max 1 --schedulers tiles --spp 1 --width 24 --repeat 1 --ranks-max 2 ";
  const auto r = test::run_command(scaling + "--out " + quote(dir + "/out"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream csv(slurp(dir + "/out/scaling.csv"));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line.substr(line.rfind(',')), ",ranks");
  std::vector<std::string> rows;
  while (std::getline(csv, line)) rows.push_back(line);
  ASSERT_EQ(rows.size(), 2u);  // 1 and 2 ranks of one thread
  EXPECT_EQ(rows[0].substr(rows[0].rfind(',')), ",1");
  EXPECT_EQ(rows[1].substr(rows[1].rfind(',')), ",2");
  EXPECT_NE(slurp(dir + "/out/scaling.md").find("| tiles | 2 | 1 |"), std::string::npos);
  const auto bad = test::run_command(scaling + "--out " + quote(dir + "/bad") + " --launcher 'no-such-launcher -n {}'");
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("2 ranks: `no-such-launcher` failed with exit code 127"), std::string::npos) << bad.err;
}

// A time limit stops every rank after the same waves: a millisecond lets the first wave (which
// always finishes) alone run, in one process or three, and the partial frames are the same.
TEST_F(MpiFaults, ATimeLimitStopsEveryRankAfterTheSameWaves) {
  const std::string dir = test::make_temp_dir("mpi-time-limit");
  const std::string opts = "-q --spp 256 --tile-size 8 --time-limit 0.001";
  ASSERT_EQ(test::run_command(render_args(dir + "/one.exr", opts)).exit_code, 0);
  const auto r = test::run_command(mpirun(3) + render_args(dir + "/three.exr", opts));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const std::string f : {"/one.exr", "/three.exr"}) {
    EXPECT_EQ(test::exr_int(dir + f, "partial"), 1) << f;
    EXPECT_EQ(test::exr_int(dir + f, "samplesPerPixel"), 1) << f;
  }
  expect_same_pixels(dir + "/one.exr", dir + "/three.exr");
}

// A rank stopped (SIGSTOP: alive, not answering) mid-frame: rank 0's watchdog ends the job
// within --rank-timeout of waiting for it, with one message naming it, and the checkpoint
// written before resumes to the uninterrupted frame's bits.
TEST_F(MpiFaults, AStoppedRankEndsTheJobWithinTheTimeout) {
  const std::string dir = test::make_temp_dir("mpi-hung");
  const std::string out = dir + "/h.exr", opts = "-q --spp 256 --checkpoint 0.001";
  const test::SignalledJob job =
      test::run_signalled(out, "STOP", "OMPI_COMM_WORLD_RANK=2", mpirun(3) + render_args(out, opts + " --rank-timeout 2"));
  EXPECT_EQ(job.rc, 1) << job.log;
  EXPECT_LT(job.ms, 15000) << "the timeout is 2 s";
  EXPECT_GE(job.ms, 2000) << "gave up before the timeout";
  EXPECT_EQ(count(job.log, "has not answered"), 1u) << job.log;
  EXPECT_NE(job.log.find("tessera: error: rank 2 has not answered for 2 s"), std::string::npos) << job.log;
  test::expect_resumes_to_whole(out, opts);
}

// A rank stopped inside Open MPI, holding the lock of rank 0's window that accumulates take
// (osc/rdma and osc/sm do each one under it, in shared memory): the other ranks spin inside
// their next operation, where no watchdog between calls can act; with one alone this job
// hung until killed (CI once; here every time). gdb stops rank 2 there (a breakpoint on the
// operator Open MPI applies under the lock, then SIGSTOP and detach); rank 0's call watch
// ends the job within the timeout, with one message, and the checkpoint resumes. gdb reads
// no debug information and no library's symbols but Open MPI's: attaching stops the rank, and
// reading the 200 MB sanitizer build's took 2.1-2.8 s (0.7-0.9 s so), longer than a 2 s
// timeout, which then ended the job before the breakpoint (CI once, under ASan); 4 s leaves
// the attach a margin.
TEST_F(MpiFaults, ARankStoppedInsideOpenMpisLockEndsTheJobWithinTheTimeout) {
  if (std::system("command -v gdb > /dev/null 2>&1") != 0) GTEST_SKIP() << "gdb not found (apt-get install gdb)";
  const std::string dir = test::make_temp_dir("mpi-lock");
  // 2048 spp: the job (3 s at 1024 spp here) still runs when gdb has attached, under a second
  // after the first checkpoint, on a machine a few times faster too.
  const std::string out = dir + "/h.exr", opts = "-q --spp 2048 --checkpoint 0.001";
  const std::string stop_in_lock =
      "gdb --readnever -p \"$p\" -batch -iex 'set auto-solib-add off' -ex 'sharedlibrary libmpi' "
      "-ex 'break ompi_osc_base_sndrcv_op' -ex continue -ex \"shell kill -STOP $p\" -ex detach > \"$out.gdb\" 2>&1";
  const test::SignalledJob job = test::run_script(out, test::job_script("OMPI_COMM_WORLD_RANK=2", stop_in_lock),
                                                  mpirun(3, 60) + render_args(out, opts + " --rank-timeout 4"));
  std::ifstream gdb_log(out + ".gdb");
  const std::string gdb((std::istreambuf_iterator<char>(gdb_log)), std::istreambuf_iterator<char>());
  ASSERT_NE(gdb.find("hit Breakpoint 1"), std::string::npos) << "rank 2 was not stopped in the lock:\n" << gdb;
  EXPECT_EQ(job.rc, 1) << job.log;
  EXPECT_LT(job.ms, 15000) << "the timeout is 4 s";
  EXPECT_EQ(count(job.log, "error:"), 1u) << job.log;
  EXPECT_NE(job.log.find("tessera: error: an MPI call has not returned for 4"), std::string::npos) << job.log;
  test::expect_resumes_to_whole(out, opts);
}

// Rank 0 stopped where the ranks' one-sided operations need it to answer: Open MPI's osc/pt2pt
// over TCP makes each remote atomic a message that rank 0 serves (on one machine the default,
// osc/sm, does them in shared memory without it). Rank 1, waiting for the counter or for rank
// 0's notes, gives up within the timeout (plus the 5 s ranks other than 0 wait longer),
// naming rank 0; with a blocking MPI_Win_flush it waited forever (here: until the test's
// 40 s, exit 124). Ending the job, Open MPI continues the stopped rank 0 before it terminates
// it (SIGCONT, then SIGTERM): woken, rank 0 may find rank 1 silent for its own timeout and say
// so (CI once, under ASan), after rank 1's message, which must come first.
TEST_F(MpiFaults, AStoppedRankZeroEndsTheJobOverTcp) {
  const std::string dir = test::make_temp_dir("mpi-hung0");
  const std::string out = dir + "/h.exr", opts = "-q --spp 1024 --checkpoint 0.001 --rank-timeout 2";
  const std::string tcp = "--mca btl tcp,self --mca osc pt2pt ";
  const test::SignalledJob job =
      test::run_signalled(out, "STOP", "OMPI_COMM_WORLD_RANK=0", mpirun(2, 40) + tcp + render_args(out, opts));
  EXPECT_EQ(job.rc, 1) << job.log;
  EXPECT_LT(job.ms, 30000) << "the timeout is 2 s";
  EXPECT_GE(job.ms, 2000) << "gave up before the timeout";
  const std::string named = "tessera: rank 1: error: rank 0 has not answered for 7 s";
  const std::size_t at = job.log.find(named);
  ASSERT_NE(at, std::string::npos) << "the timeout and the 5 s ranks other than 0 wait longer\n" << job.log;
  EXPECT_EQ(job.log.find("error:"), at + named.find("error:")) << "rank 1's message comes first\n" << job.log;
  EXPECT_LE(count(job.log, "error:"), 2u) << job.log;
}

// A sequence with whole frames to ranks: a rank that has finished its frames waits for the
// others' (up to a whole frame) with the watchdog on; the others give a sign of life between
// waves, so a frame longer than the timeout is no fault, and the job ends well. The timeout is
// a quarter of a frame as measured first in one process: 16 times a wave (4096 spp are 64
// waves), a quarter of the wait, whatever the machine's speed and load.
TEST_F(MpiFaults, RanksRenderingWholeFramesAreAliveBetweenWaves) {
  const std::string dir = test::make_temp_dir("mpi-alive");
  const std::string small = quote(test::tessera_exe()) + " render " + quote(test::scene_path("cornell-box/cornell-box.gltf")) +
                            " --width 20 --height 18 --spp 4096 ";
  const auto one = test::run_command(small + "--frame 0 -o " + quote(dir + "/one.exr"));
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const double frame = std::stod(one.err.substr(one.err.find(", render ") + 9));
  const double timeout = std::max(0.2, frame / 4);
  const auto r = test::run_command(mpirun(2) + small + "--frames 0:2 -o " + quote(dir + "/f.#.exr") + " --rank-timeout " +
                                   std::to_string(timeout));
  ASSERT_EQ(r.exit_code, 0) << "timeout " << timeout << " s\n" << r.err;
  EXPECT_NE(r.err.find("3 rendered by 2 ranks"), std::string::npos) << r.err;
}

// Ctrl-C at mpirun: Open MPI sends the ranks SIGCONT, SIGTERM odls_base_sigkill_timeout seconds
// later, SIGKILL as long again after. They stop as one process does: the tiles in flight
// finish, rank 0 writes the partial frame and says so once, and the frame resumes to the
// uninterrupted bits. mpirun's own exit code is 1 for a job it was told to stop; a SIGTERM sent
// to the ranks themselves (as Slurm's scancel does) gives 130. The timeout is 3 s, not the
// default 1 (docs/distributed.md): under ASan on a loaded machine, finishing a tile of a
// 64-sample wave and writing took longer than a second once, and SIGKILL came first. (4096
// spp: the job, 7.6 s here without sanitizers, still runs when the SIGTERM comes.)
TEST_F(MpiFaults, ASignalStopsTheRanksAsItStopsOneProcess) {
  const std::string dir = test::make_temp_dir("mpi-signal");
  const std::string opts = "--spp 4096 --checkpoint 0.001";
  const std::pair<std::string, int> cases[] = {{"", 1}, {"OMPI_COMM_WORLD_RANK=", 130}};
  for (const auto& [which, code] : cases) {
    const std::string out = dir + "/s" + std::to_string(code) + ".exr";
    const test::SignalledJob job =
        test::run_signalled(out, which.empty() ? "INT" : "TERM", which,
                            mpirun(2) + "--mca odls_base_sigkill_timeout 3 " + render_args(out, opts));
    EXPECT_EQ(job.rc, code) << job.log;
    EXPECT_GE(job.ms, 0) << job.log;
    EXPECT_LT(job.ms, 15000);
    EXPECT_EQ(count(job.log, "tessera: interrupted: finishing the work in flight"), 1u) << job.log;
    EXPECT_NE(job.log.find("spp; wrote " + out), std::string::npos) << "rank 0 did not write the frame:\n" << job.log;
    EXPECT_EQ(test::exr_int(out, "partial"), 1) << job.log;
  }
  // The frame stopped through mpirun, finished in one process: the uninterrupted bits.
  test::expect_resumes_to_whole(dir + "/s1.exr", "-q " + opts);
}

}  // namespace
}  // namespace tessera
