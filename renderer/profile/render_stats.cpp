#include "renderer/profile/render_stats.h"

#include <time.h>

#include <algorithm>

namespace tessera {

LoadBalance load_balance(const std::vector<ThreadStats>& threads, const std::vector<WaveStats>& waves) {
  LoadBalance b;
  if (!waves.empty()) b.wall = waves.back().end - waves.front().start;
  double busy = 0.0, most = 0.0, cpu = 0.0;
  for (const ThreadStats& t : threads) {
    busy += t.busy;
    cpu += t.cpu;
    most = std::max(most, t.busy);
  }
  const double n = static_cast<double>(threads.size());
  if (n > 0 && b.wall > 0.0) b.efficiency = busy / (n * b.wall);
  if (busy > 0.0) b.imbalance = most / (busy / n);
  if (busy > 0.0) b.cpu_share = cpu / busy;
  for (const WaveStats& w : waves) b.tail += w.tail;
  return b;
}

std::vector<double> tile_seconds(const FrameProfile& profile, TileClock clock) {
  const std::vector<double>& items = clock == TileClock::wall ? profile.item_seconds : profile.item_cpu_seconds;
  std::vector<double> seconds(profile.plan.tiles.size(), 0.0);
  for (std::size_t i = 0; i < profile.plan.items.size(); ++i) seconds[profile.plan.items[i].tile] += items[i];
  return seconds;
}

std::vector<float> tile_cost_image(const FrameProfile& profile) {
  const int w = profile.plan.params.width;
  std::vector<float> image(static_cast<std::size_t>(w) * profile.plan.params.height, 0.0f);
  const std::vector<double> seconds = tile_seconds(profile, TileClock::cpu);
  for (std::size_t t = 0; t < seconds.size(); ++t) {
    const Tile& r = profile.plan.tiles[t];
    for (int y = r.y0; y < r.y1; ++y)
      std::fill_n(image.begin() + static_cast<std::size_t>(y) * w + r.x0, r.x1 - r.x0, static_cast<float>(seconds[t]));
  }
  return image;
}

ProfileRecorder::ProfileRecorder(const WorkPlan& plan, int waves, bool record_tiles)
    : start_(std::chrono::steady_clock::now()), slots_(plan.params.threads), record_tiles_(record_tiles) {
  profile_.plan = plan;
  profile_.item_seconds.assign(plan.items.size(), 0.0);
  profile_.item_cpu_seconds.assign(plan.items.size(), 0.0);
  if (record_tiles) profile_.records.resize(static_cast<std::size_t>(waves) * plan.items.size());
}

void ProfileRecorder::begin_wave(int wave, int sample_begin, int sample_end) {
  wave_ = wave;
  WaveStats w;
  w.sample_begin = sample_begin;
  w.sample_end = sample_end;
  w.start = now();
  for (ThreadSlot& s : slots_) s.last_end = w.start;  // a thread given nothing ran out at once
  profile_.waves.push_back(w);
}

double ProfileRecorder::thread_cpu_seconds() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

void ProfileRecorder::record(std::size_t item, int thread, const TileRecord& run) {
  ThreadSlot& slot = slots_[thread];
  slot.busy += run.end - run.start;
  slot.cpu += run.cpu;
  slot.last_end = run.end;
  ++slot.items;
  profile_.item_seconds[item] += run.end - run.start;
  profile_.item_cpu_seconds[item] += run.cpu;
  if (!record_tiles_) return;
  TileRecord& r = profile_.records[static_cast<std::size_t>(wave_) * profile_.plan.items.size() + item];
  r = run;
  r.item = static_cast<int>(item);
  r.wave = wave_;
  r.thread = thread;
}

void ProfileRecorder::end_wave() {
  WaveStats& w = profile_.waves.back();
  w.end = now();
  double first_out = w.end;
  for (const ThreadSlot& s : slots_) first_out = std::min(first_out, s.last_end);
  w.tail = w.end - first_out;
}

FrameProfile ProfileRecorder::finish() {
  profile_.threads.resize(slots_.size());
  for (std::size_t t = 0; t < slots_.size(); ++t) {
    ThreadStats& ts = profile_.threads[t];
    ts.thread = static_cast<int>(t);
    ts.busy = slots_[t].busy;
    ts.cpu = slots_[t].cpu;
    ts.items = slots_[t].items;
  }
  profile_.balance = load_balance(profile_.threads, profile_.waves);
  for (ThreadStats& ts : profile_.threads) ts.idle = profile_.balance.wall - ts.busy;
  // Records of items a cancelled frame never ran keep thread -1 but say which they were.
  const std::size_t items = profile_.plan.items.size();
  profile_.records.resize(std::min(profile_.records.size(), profile_.waves.size() * items));
  for (std::size_t i = 0; i < profile_.records.size(); ++i) {
    profile_.records[i].item = static_cast<int>(i % items);
    profile_.records[i].wave = static_cast<int>(i / items);
  }
  return std::move(profile_);
}

}  // namespace tessera
