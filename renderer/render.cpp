#include "renderer/render.h"

#include <chrono>
#include <stdexcept>
#include <tuple>

#include <tbb/info.h>

#include "renderer/film_exchange.h"
#include "renderer/integrator/path_tracer.h"
#include "renderer/schedulers.h"

namespace tessera {

int default_thread_count() { return tbb::info::default_concurrency(); }

namespace {

struct TileCounters {
  std::uint64_t samples = 0;
  PathCounters path;
};

// The samples of `wave` a pixel still needs: from its own count to the wave's end. None
// when it converged or a resumed film has it past the wave's end; its count is the wave's
// first sample, except for a pixel an adaptive check revived (a neighbour turned noisy),
// which catches up.
std::uint32_t first_sample(const Film& film, int x, int y, SampleWave wave) {
  return film.converged(x, y) ? static_cast<std::uint32_t>(wave.end) : film.samples(x, y);
}

// One sample into the pixel's sums; the odd-numbered ones into the odd half as well.
void add_sample(PixelSums& p, int s, const glm::dvec3& radiance, const FirstHit& first, float depth) {
  ++p.samples;
  p.radiance += radiance;
  if (s % 2 == 1) p.radiance_odd += radiance;
  if (!first.hit) return;
  p.albedo += first.albedo;
  p.normal += first.normal;
  p.depth += depth;
  ++p.hits;
  if (s % 2 == 1) {
    p.albedo_odd += first.albedo;
    p.normal_odd += first.normal;
  }
}

// The samples [first_sample, wave.end) of every pixel of one tile.
void render_tile(const RenderScene& scene, const RenderCamera& camera, const PixelFilter& filter,
                 const RenderSettings& settings, const Tile& tile, SampleWave wave, Film& film,
                 TileCounters& counters) {
  PathTracerParams params;
  params.max_bounces = settings.max_bounces;
  params.light_sampling = settings.light_sampling;
  params.clamp = settings.clamp;
  params.transparent_background = settings.aovs.coverage;
  const vec3 forward = camera.forward();
  // Motion blur: each camera sample draws its time, after the film and lens positions. A
  // scene where nothing moves draws none, so its numbers and image stay what they were.
  const bool camera_moves = camera.moves(), timed = scene.moves() || camera_moves;
  const bool has_lens = camera.lens_radius > 0.0f;  // a pinhole draws no lens position
  const FrameWindow& window = settings.window;
  const float inv_w = 1.0f / (window.cropped() ? window.full_width : settings.width);
  const float inv_h = 1.0f / (window.cropped() ? window.full_height : settings.height);
  for (int y = tile.y0; y < tile.y1; ++y) {
    for (int x = tile.x0; x < tile.x1; ++x) {
      const int begin = static_cast<int>(first_sample(film, x, y, wave));
      if (begin >= wave.end) continue;
      const int fx = x + window.x, fy = y + window.y;  // in the frame: what the samples depend on
      PixelSums sums;
      for (int s = begin; s < wave.end; ++s) {
        Sampler rng(settings.sampler, fx, fy, s, settings.seed);
        const vec2 at = filter.sample(rng.next2());
        const vec2 lens = has_lens ? rng.next2() : vec2(0.5f);
        const float time = timed ? rng.next() : 0.0f;
        const Ray ray = camera.generate_ray({(fx + at.x) * inv_w, (fy + at.y) * inv_h}, lens, time);
        if (!is_finite(ray.origin) || !is_finite(ray.direction)) {  // a degenerate camera: Embree
          ++counters.path.dropped;                                 // would abort on such a ray
          ++sums.samples;
          continue;
        }
        FirstHit first;
        const glm::dvec3 radiance(trace_path(scene, params, ray, rng, first, counters.path));
        const vec3 axis = camera_moves ? -vec3(camera.camera_to_world_at(time)[2]) : forward;
        add_sample(sums, s, radiance, first, first.distance * glm::dot(ray.direction, axis));
      }
      film.add(x, y, sums);
      counters.samples += wave.end - begin;
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
  if (!resume) return Film(settings.width, settings.height, settings.aovs, settings.adaptive.on());
  if (resume->width != settings.width || resume->height != settings.height)
    throw std::invalid_argument("resumed film has another size than the render");
  if (resume->adaptive() != settings.adaptive.on() || resume->keeps_odd() != (settings.aovs.halves || settings.adaptive.on()))
    throw std::invalid_argument("resumed film was made with another adaptive sampling or halves setting");
  return Film(std::move(*resume));
}

// Whether a resumed film already has `wave`: every pixel at or past its end, and with
// adaptive sampling the convergence check after it made too (that check decides which
// pixels the next wave renders; a run stopped after the wave's last tile did not make it).
bool wave_already_done(const Film& film, SampleWave wave, int min_spp) {
  if (film.state().adaptive() && wave.end >= min_spp)
    return static_cast<std::uint32_t>(wave.end) <= film.state().checked_at;
  return film.min_samples() >= static_cast<std::uint32_t>(wave.end);
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// One wave across the ranks: this rank runs the items it takes (batches from the shared
// counter, or its block), then every rank copies in the pixels the others rendered.
void run_wave_across_ranks(RankGroup& ranks, RankScheduler scheduler, const WorkPlan& plan, WaveRunner& runner,
                           const ItemBody& body, Film& film) {
  const std::size_t n = plan.items.size();
  std::vector<std::size_t> taken;
  auto take = [&](std::size_t begin, std::size_t end) {
    runner.run_range(begin, end, body);
    for (std::size_t i = begin; i < end; ++i) taken.push_back(i);
  };
  if (scheduler == RankScheduler::stat) {
    take(n * ranks.rank() / ranks.size(), n * (ranks.rank() + 1) / ranks.size());
  } else {
    // Batches of about a quarter of a rank's fair share of threads' work: few requests, and
    // the last ones small enough to even out the ranks' finishing times.
    const std::size_t batch = std::max<std::size_t>(1, n / (4 * ranks.size() * plan.params.threads));
    ranks.start_wave(n);
    for (auto [begin, end] = ranks.next_items(batch); begin < end; std::tie(begin, end) = ranks.next_items(batch))
      take(begin, end);
  }
  std::vector<Tile> rects;
  for (const WorkItem& item : plan.items) rects.push_back(item.rect);
  const std::vector<std::vector<char>> all = ranks.all_gather(pack_tiles(film.state(), rects, taken));
  for (int r = 0; r < ranks.size(); ++r)
    if (r != ranks.rank()) unpack_tiles(film.mutable_state(), rects, all[r]);
}

}  // namespace

std::vector<SampleWave> sample_waves_of(const RenderSettings& settings) {
  if (!settings.adaptive.on()) return make_sample_waves(settings.spp);
  return make_adaptive_waves(settings.spp, adaptive_min_spp(settings.adaptive, settings.spp));
}

RenderResult render_frame(const RenderScene& scene, const RenderCamera& camera,
                          const RenderSettings& settings, RenderMonitor* monitor, FilmState* resume) {
  RenderMonitor local;
  RenderMonitor& mon = monitor ? *monitor : local;
  Film film = initial_film(settings, resume);
  const std::uint64_t resumed = total_samples(film.state());
  mon.samples_total = film.samples_left(settings.spp);
  mon.pixels_converged = film.converged_pixels();
  mon.pixels_total = film.state().pixel_count();
  const int min_spp = settings.adaptive.on() ? adaptive_min_spp(settings.adaptive, settings.spp) : 0;
  const int threads = settings.threads > 0 ? settings.threads : default_thread_count();
  const WorkPlan plan = make_work_plan(
      {settings.width, settings.height, settings.tile_size, threads, settings.scheduler, settings.tile_order});
  const std::vector<SampleWave> waves = sample_waves_of(settings);
  ProfileRecorder recorder(plan, static_cast<int>(waves.size()), settings.record_tiles);
  std::atomic<std::uint64_t> dropped{film.state().dropped}, samples{0};
  std::atomic<bool> out_of_time{false};
  RenderStats stats;
  stats.threads = threads;
  stats.ranks = settings.ranks ? settings.ranks->size() : 1;
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
  // Between waves the ranks decide together, so that they run the same waves.
  auto all_stopped = [&] { return settings.ranks ? settings.ranks->any(stopped()) : stopped(); };
  // A distributed render: every rank's samples and dropped samples, summed after each wave.
  std::uint64_t cluster_samples = 0, cluster_dropped = film.state().dropped;
  const PixelFilter filter(settings.filter);
  WaveRunner runner(plan);
  for (std::size_t w = 0; w < waves.size(); ++w) {
    if (wave_already_done(film, waves[w], min_spp)) continue;  // resumed past it
    if (all_stopped()) break;
    recorder.begin_wave(waves_run++, waves[w].begin, waves[w].end);
    const std::uint64_t samples_before = samples, dropped_before = dropped;
    const ItemBody body = [&](std::size_t i, int thread) {
      if (stopped()) return;
      TileRecord run;
      run.start = recorder.now();
      run.cpu = ProfileRecorder::thread_cpu_seconds();
      TileCounters c;
      render_tile(scene, camera, filter, settings, plan.items[i].rect, waves[w], film, c);
      run.cpu = ProfileRecorder::thread_cpu_seconds() - run.cpu;
      run.end = recorder.now();
      run.samples = c.samples;
      run.rays = c.path.rays;
      recorder.record(i, thread, run);
      samples += c.samples;
      dropped += c.path.dropped;
      mon.samples_done += c.samples;
      mon.rays += c.path.rays;
    };
    if (settings.ranks) {
      run_wave_across_ranks(*settings.ranks, settings.rank_scheduler, plan, runner, body, film);
      cluster_samples += settings.ranks->sum(samples - samples_before);
      cluster_dropped += settings.ranks->sum(dropped - dropped_before);
      mon.samples_done = cluster_samples;
    } else {
      runner.run(body);
    }
    recorder.end_wave();
    first_wave = false;
    // Only after a whole wave (a stopped one skipped tiles), and not after the last.
    if (settings.adaptive.on() && waves[w].end >= min_spp && w + 1 < waves.size() && !all_stopped()) {
      mon.pixels_converged = check_convergence(
          film.mutable_state(), {settings.adaptive.threshold, static_cast<std::uint32_t>(min_spp),
                                 static_cast<std::uint32_t>(waves[w].end)});
      mon.samples_total = mon.samples_done + film.samples_left(settings.spp);
    }
    const bool last = w + 1 == waves.size() || film.samples_left(settings.spp) == 0;
    if (settings.on_checkpoint && !last && !stopped() &&
        seconds_since(last_checkpoint) >= settings.checkpoint_interval) {
      film.set_dropped(settings.ranks ? cluster_dropped : dropped.load());
      stats.camera_samples = settings.ranks ? cluster_samples : samples.load();
      stats.dropped_samples = film.state().dropped;
      stats.seconds = seconds_since(start);
      settings.on_checkpoint(film, stats);
      last_checkpoint = std::chrono::steady_clock::now();
    }
    if (last) break;
  }
  film.set_dropped(settings.ranks ? cluster_dropped : dropped.load());
  stats.seconds = seconds_since(start);
  stats.camera_samples = settings.ranks ? cluster_samples : samples.load();
  stats.rays = settings.ranks ? settings.ranks->sum(mon.rays) : mon.rays.load();
  stats.dropped_samples = film.state().dropped;
  stats.cancelled = mon.cancel;
  stats.time_limited = out_of_time && film.samples_left(settings.spp) > 0;
  stats.converged_pixels = film.converged_pixels();
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
