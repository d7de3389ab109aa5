// Distributed rendering for real: `mpirun -np N tessera render ...` with several processes
// (Open MPI, --oversubscribe on this 2-core machine), against the same render in one process.
// Every rank renders the tiles it takes from the shared counter (or its block), and after each
// wave the ranks exchange those tiles' pixels, so the image is the single process's bit for bit.
#include <string>

#include "tests/mpi_support.h"

namespace tessera {
namespace {

using test::expect_same_pixels;
using test::mpirun;
using test::quote;
using test::render_args;

using MpiRender = test::MpiTest;

TEST_F(MpiRender, AnyNumberOfRanksGivesTheSingleProcessBits) {
  const std::string dir = test::make_temp_dir("mpi-ranks");
  const std::string opts = "-q --spp 16 --aov albedo,normal,depth,halves ";
  ASSERT_EQ(test::run_command(render_args(dir + "/one.exr", opts + "--tile-size 8")).exit_code, 0);
  for (int ranks : {1, 2, 3}) {
    const std::string out = dir + "/mpi" + std::to_string(ranks) + ".exr";
    const auto r = test::run_command(mpirun(ranks) + render_args(out, opts + "--tile-size 8"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    expect_same_pixels(dir + "/one.exr", out);
  }
  // The paper's static chunks across ranks, and another tile size and thread count.
  const auto st = test::run_command(mpirun(2) + render_args(dir + "/static.exr", opts + "--tile-size 8 --rank-scheduler static"));
  ASSERT_EQ(st.exit_code, 0) << st.err;
  expect_same_pixels(dir + "/one.exr", dir + "/static.exr");
  ASSERT_EQ(test::run_command(render_args(dir + "/one64.exr", opts + "--tile-size 64 --threads 1")).exit_code, 0);
  ASSERT_EQ(test::run_command(mpirun(3) + render_args(dir + "/mpi64.exr", opts + "--tile-size 64")).exit_code, 0);
  expect_same_pixels(dir + "/one64.exr", dir + "/mpi64.exr");
}

// Adaptive sampling decides between waves from the whole film: every rank has it.
TEST_F(MpiRender, AdaptiveSamplingStopsThePixelsOneProcessStops) {
  const std::string dir = test::make_temp_dir("mpi-adaptive");
  const std::string opts = "-q --spp 64 --noise-threshold 0.05 --tile-size 8";
  ASSERT_EQ(test::run_command(render_args(dir + "/one.exr", opts)).exit_code, 0);
  const auto r = test::run_command(mpirun(2) + render_args(dir + "/two.exr", opts));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_same_pixels(dir + "/one.exr", dir + "/two.exr");
}

// A frame stopped by --time-limit, continued under MPI, and the other way round: the
// uninterrupted frame's bits.
TEST_F(MpiRender, APartialFrameResumesAcrossRanksToTheSameBits) {
  const std::string dir = test::make_temp_dir("mpi-resume");
  const std::string opts = "-q --spp 256 --tile-size 8";
  ASSERT_EQ(test::run_command(render_args(dir + "/whole.exr", opts)).exit_code, 0);
  ASSERT_EQ(test::run_command(render_args(dir + "/a.exr", opts + " --time-limit 0.01")).exit_code, 0);
  ASSERT_EQ(test::exr_int(dir + "/a.exr", "partial"), 1) << "not left partial: nothing to test";
  const auto r = test::run_command(mpirun(2) + render_args(dir + "/a.exr", opts + " --resume " + quote(dir + "/a.exr")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_same_pixels(dir + "/whole.exr", dir + "/a.exr");
  ASSERT_EQ(test::run_command(mpirun(3) + render_args(dir + "/b.exr", opts + " --time-limit 0.01")).exit_code, 0);
  ASSERT_EQ(test::exr_int(dir + "/b.exr", "partial"), 1) << "not left partial: nothing to test";
  ASSERT_EQ(test::run_command(render_args(dir + "/b.exr", opts + " --resume " + quote(dir + "/b.exr"))).exit_code, 0);
  expect_same_pixels(dir + "/whole.exr", dir + "/b.exr");
}

// `render` (a command line ending in -o) on one process, on 2 and 3 ranks, and stopped early
// then resumed on 2 ranks: every image the one process's, bit for bit.
void expect_one_process_bits_on_ranks_and_after_resume(const std::string& dir, const std::string& render) {
  ASSERT_EQ(test::run_command(render + quote(dir + "/one.exr")).exit_code, 0);
  for (int ranks : {2, 3}) {
    const std::string out = dir + "/mpi" + std::to_string(ranks) + ".exr";
    const auto r = test::run_command(mpirun(ranks) + render + quote(out));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    expect_same_pixels(dir + "/one.exr", out);
  }
  ASSERT_EQ(test::run_command(render + quote(dir + "/a.exr") + " --time-limit 0.01").exit_code, 0);
  ASSERT_EQ(test::exr_int(dir + "/a.exr", "partial"), 1) << "not left partial: nothing to test";
  const auto r = test::run_command(mpirun(2) + render + quote(dir + "/a.exr") + " --resume " + quote(dir + "/a.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_same_pixels(dir + "/one.exr", dir + "/a.exr");
}

// A vertex's light from the light tree (1,024 lamps): its own draw of the sampler, so any
// number of ranks, and a frame resumed, gives the single process's bits.
TEST_F(MpiRender, TheLightTreeGivesTheSingleProcessBitsOnAnyRanksAndAfterResume) {
  expect_one_process_bits_on_ranks_and_after_resume(
      test::make_temp_dir("mpi-light-tree"),
      quote(test::tessera_exe()) + " render " + quote(test::scene_path("many-lights/street-of-lamps.gltf")) +
          " -q --width 48 --height 27 --spp 256 --tile-size 8 --light-tree on -o ");
}

// Path guiding across ranks: each rank records what its tiles' paths found, the ranks add
// their records (integers) after each learning wave, and every rank finishes the same round:
// 1, 2 and 3 ranks and a resumed render give the one process's image bit for bit.
TEST_F(MpiRender, GuidingGivesTheSingleProcessBitsOnAnyRanksAndAfterResume) {
  expect_one_process_bits_on_ranks_and_after_resume(
      test::make_temp_dir("mpi-guiding"),
      quote(test::tessera_exe()) + " render " + quote(test::scene_path("hard-light/caustic.gltf")) +
          " -q --width 48 --height 27 --spp 64 --tile-size 8 --background 0 --guiding on -o ");
}

// A sequence with at least as many frames as ranks: whole frames go to the ranks, each taken
// from the shared counter; with fewer, the ranks share every frame's tiles. Either way every
// frame file is the one process's, bit for bit.
TEST_F(MpiRender, SequencesHandWholeFramesToRanks) {
  const std::string dir = test::make_temp_dir("mpi-frames");
  const std::string box = quote(test::tessera_exe()) + " render " +
                          quote(test::scene_path("khronos/BoxAnimated/glTF-Binary/BoxAnimated.glb")) +
                          " --width 40 --spp 8 --seed 4 ";
  ASSERT_EQ(test::run_command(box + "-q --frames 0:4 -o " + quote(dir + "/one.#.exr")).exit_code, 0);
  const auto whole = test::run_command(mpirun(2) + box + "--frames 0:4 -o " + quote(dir + "/two.#.exr"));
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  EXPECT_NE(whole.err.find("frames 0:4: 5 rendered by 2 ranks, 0 skipped"), std::string::npos) << whole.err;
  for (int f = 0; f <= 4; ++f)
    expect_same_pixels(dir + "/one." + std::to_string(f) + ".exr", dir + "/two." + std::to_string(f) + ".exr");
  const auto tiles = test::run_command(mpirun(3) + box + "-q --frames 3:4 -o " + quote(dir + "/three.#.exr"));
  ASSERT_EQ(tiles.exit_code, 0) << tiles.err;
  for (int f = 3; f <= 4; ++f)
    expect_same_pixels(dir + "/one." + std::to_string(f) + ".exr", dir + "/three." + std::to_string(f) + ".exr");
}

// A rank killed mid-frame (SIGKILL, as a crashed or lost node): the job ends with a non-zero
// exit within a bounded time (Open MPI notices and ends the other ranks), and the checkpoint
// rank 0 wrote before it resumes, in one process, to the uninterrupted frame's bits.
TEST_F(MpiRender, AKilledRankEndsTheJobAndTheCheckpointResumes) {
  const std::string dir = test::make_temp_dir("mpi-kill");
  const std::string out = dir + "/k.exr", opts = "-q --spp 256 --checkpoint 0.001";
  const test::SignalledJob job = test::run_signalled(out, "9", "OMPI_COMM_WORLD_RANK=1", mpirun(2) + render_args(out, opts));
  EXPECT_NE(job.rc, 0) << "the job went on without its rank";
  EXPECT_GE(job.ms, 0) << job.log;
  EXPECT_LT(job.ms, 60000) << "the job took too long to end";
  test::expect_resumes_to_whole(out, opts);
}

// Rank 0 speaks for all: one summary; and a scene no rank can read ends the whole job with
// exit 2 and the file named.
TEST_F(MpiRender, RankZeroSpeaksAndAFailureEndsTheJob) {
  const std::string dir = test::make_temp_dir("mpi-speak");
  const auto r = test::run_command(mpirun(3) + render_args(dir + "/f.exr", "--spp 16"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::size_t wrote = 0;
  for (std::size_t at = r.err.find("wrote "); at != std::string::npos; at = r.err.find("wrote ", at + 1)) ++wrote;
  EXPECT_EQ(wrote, 1u) << r.err;
  EXPECT_NE(r.err.find("40x36, 16 spp"), std::string::npos) << r.err;
  const auto bad = test::run_command(mpirun(2) + quote(test::tessera_exe()) + " render " + quote(dir + "/missing.gltf") +
                                     " -o " + quote(dir + "/x.exr"));
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
  EXPECT_NE(bad.err.find(dir + "/missing.gltf"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace tessera
