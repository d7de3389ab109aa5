// The path guide of one frame (renderer/guiding/path_guide.h) and its rounds. It learns from
// the first sample waves, up to a quarter of the samples per pixel (with adaptive sampling,
// no further than the waves every pixel takes), one round per wave; the waves after them are
// guided by what the last round learnt. Every wave's samples, the learning ones too, go to
// the film: each is unbiased whatever the guide.
#pragma once

#include <memory>
#include <vector>

#include "renderer/guiding/path_guide.h"
#include "renderer/parallel/rank_group.h"
#include "renderer/parallel/tile_scheduler.h"
#include "renderer/render/render.h"

namespace tessera {

class FrameGuide {
 public:
  FrameGuide(const RenderScene& scene, const RenderCamera& camera, const RenderSettings& settings);
  ~FrameGuide();
  PathGuide* guide() const { return guide_.get(); }  // null: the frame is not guided
  bool learns_from(SampleWave wave) const { return guide_ && wave.end <= learn_end_; }
  // `wave` of the whole frame traced for the guide alone, no film: what a crop, a resumed
  // render and a pixel traced alone do to learn what the whole frame's render learns.
  void learn_alone(SampleWave wave);
  // After a wave it learnt from: the ranks' records added together (when they shared the
  // wave's tiles: `ranks`), the round finished.
  void finish_round(SampleWave wave, RankGroup* ranks);

 private:
  const RenderScene& scene_;
  const RenderCamera& camera_;
  const RenderSettings& settings_;
  std::unique_ptr<PathGuide> guide_;
  struct WholeFrame;  // what learn_alone traces with, built at its first call
  std::unique_ptr<WholeFrame> whole_;
  int learn_end_ = 0;  // it learns from the waves that end at or before this sample
};

}  // namespace tessera
