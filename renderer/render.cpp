#include "renderer/render.h"

#include <chrono>
#include <stdexcept>

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

// All samples [wave.begin, wave.end) of every pixel of one tile that has exactly
// wave.begin samples: a resumed film's pixels that are ahead skip the wave.
void render_tile(const RenderScene& scene, const RenderCamera& camera, const RenderSettings& settings,
                 const Tile& tile, SampleWave wave, Film& film, TileCounters& counters) {
  PathTracerParams params;
  params.max_bounces = settings.max_bounces;
  params.light_sampling = settings.light_sampling;
  params.clamp = settings.clamp;
  const vec3 forward = camera.forward();
  const float inv_w = 1.0f / settings.width, inv_h = 1.0f / settings.height;
  for (int y = tile.y0; y < tile.y1; ++y) {
    for (int x = tile.x0; x < tile.x1; ++x) {
      if (film.samples(x, y) != static_cast<std::uint32_t>(wave.begin)) continue;
      glm::dvec3 sum(0.0);
      vec3 albedo(0.0f), normal(0.0f);
      float depth = 0.0f;
      std::uint32_t hits = 0;
      for (int s = wave.begin; s < wave.end; ++s) {
        Sampler rng(settings.sampler, x, y, s, settings.seed);
        const vec2 jitter = rng.next2();
        const vec2 lens = rng.next2();
        const Ray ray = camera.generate_ray({(x + jitter.x) * inv_w, (y + jitter.y) * inv_h}, lens);
        if (!is_finite(ray.origin) || !is_finite(ray.direction)) {  // a degenerate camera: Embree
          ++counters.path.dropped;                                 // would abort on such a ray
          continue;
        }
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
      counters.samples += wave.end - wave.begin;
    }
  }
}

std::uint64_t total_samples(const FilmState& film) {
  std::uint64_t n = 0;
  for (std::uint32_t s : film.samples) n += s;
  return n;
}

// The film to start from: empty, or the resumed one, checked against the settings.
Film initial_film(const RenderSettings& settings, FilmState* resume) {
  if (!resume) return Film(settings.width, settings.height, settings.aovs);
  if (resume->width != settings.width || resume->height != settings.height)
    throw std::invalid_argument("resumed film has another size than the render");
  return Film(std::move(*resume));
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

RenderResult render_frame(const RenderScene& scene, const RenderCamera& camera,
                          const RenderSettings& settings, RenderMonitor* monitor, FilmState* resume) {
  RenderMonitor local;
  RenderMonitor& mon = monitor ? *monitor : local;
  Film film = initial_film(settings, resume);
  const std::uint64_t resumed = total_samples(film.state());
  mon.samples_total = static_cast<std::uint64_t>(settings.width) * settings.height * settings.spp - resumed;
  const int threads = settings.threads > 0 ? settings.threads : default_thread_count();
  const WorkPlan plan = make_work_plan(
      {settings.width, settings.height, settings.tile_size, threads, settings.scheduler, settings.tile_order});
  const std::vector<SampleWave> waves = make_sample_waves(settings.spp);
  ProfileRecorder recorder(plan, static_cast<int>(waves.size()), settings.record_tiles);
  std::atomic<std::uint64_t> dropped{film.state().dropped}, samples{0};
  std::atomic<bool> out_of_time{false};
  RenderStats stats;
  stats.threads = threads;
  stats.resumed_samples = resumed;

  const auto start = std::chrono::steady_clock::now();
  auto last_checkpoint = start;
  int waves_run = 0;  // the profile numbers the waves this run ran
  bool first_wave = true;  // of this run: it always finishes, so a time limit leaves an image
  auto stopped = [&] {
    if (mon.cancel.load(std::memory_order_relaxed) || out_of_time.load(std::memory_order_relaxed)) return true;
    if (settings.time_limit > 0.0 && !first_wave && seconds_since(start) >= settings.time_limit)
      out_of_time.store(true, std::memory_order_relaxed);
    return out_of_time.load(std::memory_order_relaxed);
  };
  WaveRunner runner(plan);
  for (std::size_t w = 0; w < waves.size(); ++w) {
    if (film.min_samples() >= static_cast<std::uint32_t>(waves[w].end)) continue;  // resumed past it
    if (stopped()) break;
    recorder.begin_wave(waves_run++, waves[w].begin, waves[w].end);
    runner.run([&](std::size_t i, int thread) {
      if (stopped()) return;
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
    first_wave = false;
    const bool last = w + 1 == waves.size();
    if (settings.on_checkpoint && !last && !stopped() &&
        seconds_since(last_checkpoint) >= settings.checkpoint_interval) {
      film.set_dropped(dropped);
      stats.camera_samples = samples;
      stats.dropped_samples = dropped;
      stats.seconds = seconds_since(start);
      settings.on_checkpoint(film, stats);
      last_checkpoint = std::chrono::steady_clock::now();
    }
  }
  film.set_dropped(dropped);
  stats.seconds = seconds_since(start);
  stats.camera_samples = samples;
  stats.rays = mon.rays;
  stats.dropped_samples = dropped;
  stats.cancelled = mon.cancel;
  stats.time_limited = out_of_time && film.min_samples() < static_cast<std::uint32_t>(settings.spp);
  RenderResult result;
  result.stats = stats;
  result.profile = recorder.finish();
  result.stats.efficiency = result.profile.balance.efficiency;
  result.stats.imbalance = result.profile.balance.imbalance;
  result.image = film.resolve();
  result.film = film.take_state();
  return result;
}

}  // namespace tessera
