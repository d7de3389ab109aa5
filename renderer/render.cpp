#include "renderer/render.h"

#include <chrono>

#include <tbb/info.h>

#include "renderer/integrator/path_tracer.h"
#include "renderer/schedulers.h"

namespace tessera {

int default_thread_count() { return tbb::info::default_concurrency(); }

namespace {

struct TileCounters {
  std::uint64_t samples = 0;
  PathCounters path;
};

// All samples [wave.begin, wave.end) of every pixel of one tile.
void render_tile(const RenderScene& scene, const RenderCamera& camera, const RenderSettings& settings,
                 const Tile& tile, SampleWave wave, Film& film, TileCounters& counters) {
  const PathTracerParams params{settings.max_bounces};
  const vec3 forward = camera.forward();
  const float inv_w = 1.0f / settings.width, inv_h = 1.0f / settings.height;
  for (int y = tile.y0; y < tile.y1; ++y) {
    for (int x = tile.x0; x < tile.x1; ++x) {
      glm::dvec3 sum(0.0);
      vec3 albedo(0.0f), normal(0.0f);
      float depth = 0.0f;
      std::uint32_t hits = 0;
      for (int s = wave.begin; s < wave.end; ++s) {
        SampleStream rng(x, y, s, settings.seed);
        const vec2 jitter = rng.next2();
        const vec2 lens = rng.next2();
        const Ray ray = camera.generate_ray({(x + jitter.x) * inv_w, (y + jitter.y) * inv_h}, lens);
        FirstHit first;
        sum += glm::dvec3(trace_path(scene, params, ray, rng, first, counters.path));
        if (first.hit) {
          albedo += first.albedo;
          normal += first.normal;
          depth += first.distance * glm::dot(ray.direction, forward);
          ++hits;
        }
      }
      film.add(x, y, wave.end - wave.begin, sum, albedo, normal, depth, hits);
    }
  }
  counters.samples += static_cast<std::uint64_t>(tile.pixel_count()) * (wave.end - wave.begin);
}

}  // namespace

RenderResult render_frame(const RenderScene& scene, const RenderCamera& camera,
                          const RenderSettings& settings, RenderMonitor* monitor) {
  RenderMonitor local;
  RenderMonitor& mon = monitor ? *monitor : local;
  mon.samples_total = static_cast<std::uint64_t>(settings.width) * settings.height * settings.spp;
  Film film(settings.width, settings.height, settings.aovs);
  const int threads = settings.threads > 0 ? settings.threads : default_thread_count();
  const WorkPlan plan = make_work_plan(
      {settings.width, settings.height, settings.tile_size, threads, settings.scheduler, settings.tile_order});
  const std::vector<SampleWave> waves = make_sample_waves(settings.spp);
  ProfileRecorder recorder(plan, static_cast<int>(waves.size()), settings.record_tiles);
  std::atomic<std::uint64_t> dropped{0}, samples{0};

  const auto start = std::chrono::steady_clock::now();
  WaveRunner runner(plan);
  for (std::size_t w = 0; w < waves.size(); ++w) {
    if (mon.cancel.load(std::memory_order_relaxed)) break;
    recorder.begin_wave(static_cast<int>(w), waves[w].begin, waves[w].end);
    runner.run([&](std::size_t i, int thread) {
      if (mon.cancel.load(std::memory_order_relaxed)) return;
      TileRecord run;
      run.start = recorder.now();
      run.cpu = ProfileRecorder::thread_cpu_seconds();
      TileCounters c;
      render_tile(scene, camera, settings, plan.items[i].rect, waves[w], film, c);
      run.cpu = ProfileRecorder::thread_cpu_seconds() - run.cpu;
      run.end = recorder.now();
      run.samples = c.samples;
      run.rays = c.path.rays;
      recorder.record(i, thread, run);
      samples += c.samples;
      dropped += c.path.dropped;
      mon.samples_done += c.samples;
      mon.rays += c.path.rays;
    });
    recorder.end_wave();
  }
  RenderResult result;
  result.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.stats.camera_samples = samples;
  result.stats.rays = mon.rays;
  result.stats.dropped_samples = dropped;
  result.stats.threads = threads;
  result.stats.cancelled = mon.cancel;
  result.profile = recorder.finish();
  result.stats.efficiency = result.profile.balance.efficiency;
  result.stats.imbalance = result.profile.balance.imbalance;
  result.image = film.resolve();
  return result;
}

}  // namespace tessera
