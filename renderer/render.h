// Renders one frame: sample waves over the whole image, the tiles of each wave shared among
// the threads by the chosen scheduler, every random number a function of (pixel, sample,
// dimension, seed).
#pragma once

#include <atomic>
#include <cstdint>

#include "renderer/camera.h"
#include "renderer/film.h"
#include "renderer/render_scene.h"
#include "renderer/render_stats.h"

namespace tessera {

struct RenderSettings {
  int width = 640, height = 360;
  int spp = 16;
  int max_bounces = 8;
  int threads = 0;  // 0 = all cores
  int tile_size = 32;
  std::uint32_t seed = 0;
  AovSelection aovs;
  SchedulerKind scheduler = SchedulerKind::tiles;
  TileOrder tile_order = TileOrder::scanline;
  bool record_tiles = false;  // keep a TileRecord per item and wave in RenderResult::profile
};

// Live counters a progress display may poll while rendering, and a way to stop early
// (tiles already started finish; the frame keeps every finished sample).
struct RenderMonitor {
  std::atomic<std::uint64_t> samples_done{0};  // camera samples finished
  std::atomic<std::uint64_t> rays{0};
  std::uint64_t samples_total = 0;  // set by render_frame before work starts
  std::atomic<bool> cancel{false};
};

struct RenderStats {
  double seconds = 0.0;
  std::uint64_t camera_samples = 0, rays = 0, dropped_samples = 0;
  int threads = 0;
  bool cancelled = false;
  double efficiency = 1.0, imbalance = 1.0;  // see LoadBalance
};

struct RenderResult {
  FrameImage image;
  RenderStats stats;
  FrameProfile profile;
};

RenderResult render_frame(const RenderScene& scene, const RenderCamera& camera,
                          const RenderSettings& settings, RenderMonitor* monitor = nullptr);

// The thread count --threads 0 means.
int default_thread_count();

}  // namespace tessera
