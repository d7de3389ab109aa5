// Renders one frame: sample waves over the whole image, the tiles of each wave shared among
// the threads by the chosen scheduler, every random number a function of (pixel, sample,
// dimension, seed).
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>

#include "renderer/sampling/adaptive_sampling.h"
#include "renderer/camera/camera.h"
#include "renderer/film/film.h"
#include "renderer/guiding/guiding_use.h"
#include "renderer/parallel/rank_group.h"
#include "renderer/camera/pixel_filter.h"
#include "renderer/integrator/path_tracer.h"
#include "renderer/scene/render_scene.h"
#include "renderer/profile/render_stats.h"

namespace tessera {

struct RenderStats;

struct RenderSettings {
  int width = 640, height = 360;  // the film: the frame, or its cropped region
  // With a crop, the film is a region of a larger frame: each of its pixels gets exactly
  // the samples (and the camera rays) that pixel gets when the whole frame is rendered.
  FrameWindow window;
  int spp = 16;
  int max_bounces = 8;
  int threads = 0;  // 0 = all cores
  int tile_size = 32;
  std::uint32_t seed = 0;
  SamplerKind sampler = SamplerKind::sobol;
  PixelFilterParams filter;
  AovSelection aovs;
  SchedulerKind scheduler = SchedulerKind::tiles;
  TileOrder tile_order = TileOrder::scanline;
  bool record_tiles = false;  // keep a TileRecord per item and wave in RenderResult::profile
  // Stop starting tiles once this many seconds of sampling have passed (0: no limit); the
  // first wave of a run always finishes, so there is an image. spp is then the most.
  double time_limit = 0.0;
  // Called between waves, at most every checkpoint_interval seconds, with the film so far
  // (the last wave excepted: the finished frame follows at once).
  double checkpoint_interval = 0.0;
  std::function<void(const Film&, const RenderStats&)> on_checkpoint;
  LightSampling light_sampling = LightSampling::Mis;
  // With MIS, the probability that a path vertex samples an emitter; 0: from a pilot of the
  // scene's direct light (integrator/emitter_pick.h). Any value in (0, 1] gives the same image
  // in expectation.
  float emitter_pick = 0.0f;
  float clamp = 0.0f;  // > 0: clamp each sample's luminance (biased, off by default)
  // Whether a path vertex samples one punctual light from the light tree or every one
  // (renderer/lights/light_tree.h; Auto: the tree with more than kLightTreeAutoMin lights), and
  // whether the emissive triangle it samples is chosen by their light tree or by power
  // (AreaLights::tree_used; Auto: AreaLights::auto_tree).
  LightTreeUse light_tree = LightTreeUse::Auto;
  // Path guiding (renderer/guiding/path_guide.h, render/frame_guide.h): paths draw their
  // directions in part from the incident light learnt in the first waves (Auto:
  // renderer/guiding/guiding_use.h). The same image in expectation.
  GuidingUse guiding = GuidingUse::Auto;
  // Camera rays that provably miss everything are not traced (renderer/camera/camera_coverage.h);
  // false traces every one, the same image: what the tests compare with.
  bool cull_camera_rays = true;
  AdaptiveSampling adaptive;  // off by default: every pixel gets spp
  // A distributed render: the ranks share each wave's tiles (a global counter, or a block
  // each) and exchange what they rendered after it, so every rank ends each wave with the
  // film one process would have. Null: this process renders everything.
  RankGroup* ranks = nullptr;
  RankScheduler rank_scheduler = RankScheduler::dynamic;
  // One rank of a group rendering this frame alone (whole frames to ranks): told between
  // waves that this rank is alive, for the group's watchdog (RankGroup::alive).
  RankGroup* alive_in = nullptr;
};

// Live counters a progress display may poll while rendering, and a way to stop early
// (tiles already started finish; the frame keeps every finished sample).
struct RenderMonitor {
  std::atomic<std::uint64_t> samples_done{0};  // camera samples finished
  std::atomic<std::uint64_t> rays{0};
  // Camera samples this run takes in all: set before work starts, and with adaptive
  // sampling lowered (or raised) after each convergence check.
  std::atomic<std::uint64_t> samples_total{0};
  std::atomic<std::uint64_t> pixels_converged{0};  // adaptive sampling: after the last check
  std::atomic<std::uint64_t> pixels_total{0};  // set by render_frame before work starts
  std::atomic<bool> cancel{false};
};

struct RenderStats {
  double seconds = 0.0;
  std::uint64_t camera_samples = 0, rays = 0;  // of this run
  std::uint64_t dropped_samples = 0;  // non-finite samples left out, resumed runs included
  int ranks = 1;  // processes that rendered the frame together (MPI)
  int threads = 0;
  bool cancelled = false;  // the monitor's cancel flag stopped it
  bool time_limited = false;  // the time limit stopped it before spp
  std::uint64_t resumed_samples = 0;  // camera samples the film held before this run
  std::uint64_t converged_pixels = 0;  // adaptive sampling: pixels stopped before spp
  float emitter_pick = 1.0f;  // the probability a vertex sampled an emitter (RenderSettings)
  std::size_t light_tree_lights = 0;  // the point and spot lights a vertex chose one of; 0: no tree
  int guide_rounds = 0;  // path guiding: the rounds the guide learnt in (0: not guided)
  std::size_t guide_regions = 0;  // the regions of space it guides in
  std::size_t emitter_tree_triangles = 0;  // the emissive triangles the tree chose among; 0: by power
  double efficiency = 1.0, imbalance = 1.0;  // see LoadBalance
};

struct RenderResult {
  FrameImage image;
  RenderStats stats;
  FrameProfile profile;
  FilmState film;  // the sums behind `image`: what a checkpoint stores to resume from
};

// `resume`, when given, is a film of the same size and AOVs from an earlier, stopped run of
// the same settings (moved from): every pixel continues from its own sample count, with the
// waves the uninterrupted render would have run, so the result is the same bit for bit.
RenderResult render_frame(const RenderScene& scene, const RenderCamera& camera,
                          const RenderSettings& settings, RenderMonitor* monitor = nullptr,
                          FilmState* resume = nullptr);

// The sample waves render_frame runs: make_sample_waves, or make_adaptive_waves.
std::vector<SampleWave> sample_waves_of(const RenderSettings& settings);

// The thread count --threads 0 means.
int default_thread_count();

}  // namespace tessera
