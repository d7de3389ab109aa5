#include "renderer/render/frame_guide.h"

#include <algorithm>
#include <stdexcept>

#include "renderer/guiding/guiding_use.h"
#include "renderer/integrator/guided_scattering.h"
#include "renderer/parallel/schedulers.h"
#include "renderer/render/camera_sample.h"
#include "renderer/util/byte_stream.h"

namespace tessera {

FrameGuide::FrameGuide(const RenderScene& scene, const RenderCamera& camera, const RenderSettings& settings)
    : scene_(scene), camera_(camera), settings_(settings) {
  if (!guiding_used(settings.guiding) || settings.max_bounces < 1) return;
  guide_ = std::make_unique<PathGuide>(scene.description.bounds, guide_brightness(scene));
  learn_end_ = std::max(1, settings.spp / 4);
  if (settings.adaptive.on()) learn_end_ = std::min(learn_end_, adaptive_min_spp(settings.adaptive, settings.spp));
}

// The whole frame, uncropped, as the film's samples are the frame's; its sampler guided by
// the frame's guide and learning.
struct FrameGuide::WholeFrame {
  WholeFrame(const RenderScene& scene, const RenderCamera& camera, const RenderSettings& frame, PathGuide* guide)
      : settings(uncropped(frame)), sampler(scene, camera, settings), plan(make_work_plan(plan_params(settings))) {
    sampler.use_guide(guide, true);
  }
  static RenderSettings uncropped(RenderSettings s) {
    if (s.window.cropped()) s.width = s.window.full_width, s.height = s.window.full_height;
    s.window = FrameWindow{};
    return s;
  }
  static WorkPlanParams plan_params(const RenderSettings& s) {
    return {s.width, s.height, s.tile_size, s.threads > 0 ? s.threads : default_thread_count(), SchedulerKind::tiles};
  }
  RenderSettings settings;  // before the sampler, which keeps a reference to it
  CameraSampler sampler;
  WorkPlan plan;
};

FrameGuide::~FrameGuide() = default;

void FrameGuide::learn_alone(SampleWave wave) {
  if (!whole_) whole_ = std::make_unique<WholeFrame>(scene_, camera_, settings_, guide_.get());
  const CameraSampler& sampler = whole_->sampler;
  const WorkPlan& plan = whole_->plan;
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
    const std::vector<std::uint64_t> own = guide_->statistics();
    ByteWriter mine;
    mine.put_vector(own);
    std::vector<std::uint64_t> sum(own.size(), 0);
    for (const std::vector<char>& theirs : ranks->all_gather(mine.take())) {
      const std::vector<std::uint64_t> stats = ByteReader(theirs, "a rank's guiding records").get_vector<std::uint64_t>();
      if (stats.size() != sum.size()) throw std::runtime_error("a rank's guiding records differ in size from this rank's");
      for (std::size_t k = 0; k < sum.size(); ++k) sum[k] += stats[k];
    }
    guide_->set_statistics(sum);
  }
  guide_->finish_round(wave.end - wave.begin);
}

}  // namespace tessera
