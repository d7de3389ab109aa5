#include "renderer/render/frame_guide.h"

#include <algorithm>
#include <cstring>

#include "renderer/guiding/guiding_use.h"
#include "renderer/integrator/guided_scattering.h"
#include "renderer/parallel/schedulers.h"
#include "renderer/render/camera_sample.h"

namespace tessera {

FrameGuide::FrameGuide(const RenderScene& scene, const RenderCamera& camera, const RenderSettings& settings)
    : scene_(scene), camera_(camera), settings_(settings) {
  if (!guiding_used(settings.guiding, scene.description) || settings.max_bounces < 1) return;
  guide_ = std::make_unique<PathGuide>(scene.description.bounds, guide_brightness(scene));
  learn_end_ = std::max(1, settings.spp / 4);
  if (settings.adaptive.on()) learn_end_ = std::min(learn_end_, adaptive_min_spp(settings.adaptive, settings.spp));
}

void FrameGuide::learn_alone(SampleWave wave) const {
  RenderSettings frame = settings_;  // the whole frame, as the film's samples are the frame's
  if (frame.window.cropped()) frame.width = frame.window.full_width, frame.height = frame.window.full_height;
  frame.window = FrameWindow{};
  CameraSampler sampler(scene_, camera_, frame);
  sampler.use_guide(guide_.get(), true);
  const int threads = settings_.threads > 0 ? settings_.threads : default_thread_count();
  const WorkPlan plan = make_work_plan({frame.width, frame.height, frame.tile_size, threads, SchedulerKind::tiles});
  WaveRunner runner(plan);
  runner.run([&](std::size_t i, int) {
    const Tile& t = plan.items[i].rect;
    PathCounters counters;
    for (int y = t.y0; y < t.y1; ++y)
      for (int x = t.x0; x < t.x1; ++x)
        if (!sampler.background_only(x, y))
          sampler.sample_span(x, y, wave.begin, wave.end, counters, [](int, const CameraSampleResult&) {});
  });
}

void FrameGuide::finish_round(SampleWave wave, RankGroup* ranks) {
  if (ranks) {  // integers: the sum is the same in any order
    std::vector<std::uint64_t> stats = guide_->statistics();
    std::vector<char> mine(stats.size() * sizeof(std::uint64_t));
    std::memcpy(mine.data(), stats.data(), mine.size());
    std::fill(stats.begin(), stats.end(), 0);
    for (const std::vector<char>& theirs : ranks->all_gather(mine)) {
      for (std::size_t k = 0; k < stats.size() && (k + 1) * sizeof(std::uint64_t) <= theirs.size(); ++k) {
        std::uint64_t v;
        std::memcpy(&v, theirs.data() + k * sizeof v, sizeof v);
        stats[k] += v;
      }
    }
    guide_->set_statistics(stats);
  }
  guide_->finish_round(wave.end - wave.begin);
}

}  // namespace tessera
