#include "renderer/render/render.h"

#include <chrono>
#include <stdexcept>
#include <thread>
#include <utility>

#include <tbb/info.h>

#include "renderer/render/camera_sample.h"
#include "renderer/render/frame_guide.h"
#include "renderer/parallel/film_exchange.h"
#include "renderer/integrator/path_tracer.h"
#include "renderer/profile/rank_profile.h"
#include "renderer/parallel/schedulers.h"

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
  p.radiance_sq += radiance * radiance;
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

// Samples [begin, end) of a pixel that sees only a uniform background of this radiance (no
// hit, no features): the sums add_sample makes, in closed form. The same bits: n copies of a
// float's value add up in double without rounding (n < 2^29), so n times it is exact too.
// `squares`: the film keeps the squared sums (the halves AOV); otherwise they are not worked out.
void add_background_samples(PixelSums& p, int begin, int end, const vec3& radiance, bool squares) {
  const int n = end - begin, odd = end / 2 - begin / 2;  // odd-numbered samples in [begin, end)
  p.samples += n;
  p.radiance += glm::dvec3(radiance) * static_cast<double>(n);
  p.radiance_odd += glm::dvec3(radiance) * static_cast<double>(odd);
  // The squares have up to 48 significant bits, so their sum rounds: added one by one, as
  // add_sample adds them, for the same bits.
  const glm::dvec3 square = glm::dvec3(radiance) * glm::dvec3(radiance);
  for (int k = 0; squares && k < n; ++k) p.radiance_sq += square;
}

// The samples [first_sample, wave.end) of every pixel of one tile.
void render_tile(const CameraSampler& sampler, const RenderSettings& settings, const Tile& tile, SampleWave wave,
                 Film& film, TileCounters& counters) {
  const FrameWindow& window = settings.window;
  for (int y = tile.y0; y < tile.y1; ++y) {
    for (int x = tile.x0; x < tile.x1; ++x) {
      const int begin = static_cast<int>(first_sample(film, x, y, wave));
      if (begin >= wave.end) continue;
      const int fx = x + window.x, fy = y + window.y;  // in the frame: what the samples depend on
      PixelSums sums;
      if (sampler.background_only(fx, fy)) {  // 79% of MetalRoughSpheres' samples at 640x360
        add_background_samples(sums, begin, wave.end, sampler.background_samples(wave.end - begin, counters.path),
                               !film.state().radiance_sq.empty());
      } else {
        sampler.sample_span(fx, fy, begin, wave.end, counters.path, [&](int s, const CameraSampleResult& r) {
          if (r.valid) add_sample(sums, s, glm::dvec3(r.radiance), r.first, r.depth);
          else ++sums.samples;
        });
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
  // Rank 0 holds the counter: between its tiles, its MPI thread (this one) serves the others.
  const std::thread::id mpi_thread = std::this_thread::get_id();
  const ItemBody serving = [&](std::size_t i, int thread) {
    body(i, thread);
    if (std::this_thread::get_id() == mpi_thread) ranks.progress();
  };
  // Each batch given to the threads as it comes (they do not wait at its end).
  auto take = [&](std::pair<std::size_t, std::size_t> batch) {
    for (std::size_t i = batch.first; i < batch.second; ++i) taken.push_back(i);
    return batch;
  };
  if (scheduler == RankScheduler::stat) {
    bool given = false;
    const std::pair<std::size_t, std::size_t> block{n * ranks.rank() / ranks.size(), n * (ranks.rank() + 1) / ranks.size()};
    runner.run_batches([&] { return std::exchange(given, true) ? std::pair<std::size_t, std::size_t>{0, 0} : take(block); },
                       ranks.rank() == 0 ? serving : body);
  } else {
    // Guided self-scheduling: each batch is half this rank's share of what is left, and at
    // least an item per thread. Few requests while much is left, small batches at the end,
    // so the ranks finish together even when the costly tiles come last. What is left, as
    // this rank can tell without asking again: the counter past its last batch, and past as
    // many again for each other rank (they took batches meanwhile).
    const std::size_t threads = static_cast<std::size_t>(plan.params.threads), share = 2 * ranks.size();
    auto batch_after = [&](std::size_t counter) { return std::max(threads, (n - std::min(counter, n)) / share); };
    ranks.start_wave(n);
    std::size_t batch = batch_after(0);
    runner.run_batches(
        [&] {
          const auto got = ranks.next_items(batch);
          batch = batch_after(got.first + batch * ranks.size());
          return take(got);
        },
        ranks.rank() == 0 ? serving : body);
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
  if (settings.ranks) settings.ranks->barrier();  // the ranks start their clocks together: one time line
  const double communication_before = settings.ranks ? settings.ranks->communication_seconds() : 0.0;
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
  CameraSampler sampler(scene, camera, settings);
  FrameGuide guide(scene, camera, settings);
  WaveRunner runner(plan);
  for (std::size_t w = 0; w < waves.size(); ++w) {
    if (wave_already_done(film, waves[w], min_spp)) {  // resumed past it
      if (guide.learns_from(waves[w])) guide.learn_alone(waves[w]), guide.finish_round(waves[w], nullptr);
      continue;
    }
    if (all_stopped()) break;
    // The film's tiles learn when they are the whole frame's wave: not a crop's, nor a
    // resumed one's (its pixels may hold part of the wave already).
    const bool learns = guide.learns_from(waves[w]), learns_in_film = learns && !settings.window.cropped() && !resume;
    sampler.use_guide(guide.guide(), learns_in_film);
    recorder.begin_wave(waves_run++, waves[w].begin, waves[w].end);
    const std::uint64_t samples_before = samples, dropped_before = dropped;
    const ItemBody body = [&](std::size_t i, int thread) {
      if (stopped()) return;
      TileRecord run;
      run.start = recorder.now();
      run.cpu = ProfileRecorder::thread_cpu_seconds();
      TileCounters c;
      render_tile(sampler, settings, plan.items[i].rect, waves[w], film, c);
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
    if (learns) {
      if (!learns_in_film) guide.learn_alone(waves[w]);
      guide.finish_round(waves[w], learns_in_film ? settings.ranks : nullptr);
    }
    if (settings.alive_in) settings.alive_in->alive();
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
  // Read with the clock: the sums after it (rays, the profile) wait for the slowest rank,
  // which would count as this rank's communication beyond the frame's time.
  const double communication = settings.ranks ? settings.ranks->communication_seconds() - communication_before : 0.0;
  stats.camera_samples = settings.ranks ? cluster_samples : samples.load();
  stats.rays = settings.ranks ? settings.ranks->sum(mon.rays) : mon.rays.load();
  stats.dropped_samples = film.state().dropped;
  stats.cancelled = mon.cancel;
  stats.time_limited = out_of_time && film.samples_left(settings.spp) > 0;
  stats.converged_pixels = film.converged_pixels();
  stats.emitter_pick = sampler.emitter_pick();
  stats.light_tree_lights = sampler.samples_light_tree() ? scene.light_tree.size() : 0;
  if (guide.guide()) stats.guide_rounds = guide.guide()->rounds(), stats.guide_regions = guide.guide()->regions();
  stats.emitter_tree_triangles = sampler.samples_emitter_tree() ? scene.area_lights->tree().size() : 0;
  RenderResult result;
  result.stats = stats;
  result.profile = recorder.finish();
  if (settings.ranks)
    result.profile = gather_profile(*settings.ranks, std::move(result.profile), communication);
  result.stats.efficiency = result.profile.balance.efficiency;
  result.stats.imbalance = result.profile.balance.imbalance;
  result.image = film.resolve();
  result.film = film.take_state();
  return result;
}

}  // namespace tessera
