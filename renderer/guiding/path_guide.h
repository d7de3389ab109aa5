// Path guiding (Müller et al. 2017, "Practical Path Guiding"): the incident radiance learnt
// during the render, per region of space (SpaceTree) and direction (DirectionTree), for the
// path tracer to sample directions from where light comes. It learns in rounds: during a
// sample wave the paths record what arrived along the directions they took; between waves
// the round finishes, what was learnt becomes the distribution sampled from, and the
// structure is refined for the next round.
//
// Determinism: the records are summed as integers (fixed point), so their order does not
// matter: the same waves give the same guide bit for bit whatever the threads, tiles,
// scheduler or ranks (which add their statistics together between waves).
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "renderer/description/scene.h"
#include "renderer/guiding/direction_tree.h"
#include "renderer/guiding/space_tree.h"

namespace tessera {

struct PathGuideParams {
  // A region splits in two when a round's records in it exceed this times the square root of
  // the round's samples per pixel (Müller et al.'s c; their 12,000 at 1280x720).
  double split_records = 4000.0;
  double direction_fraction = 0.01;  // a direction node splits above this share of its region's energy
  // At most 4^4 direction leaves (0.05 sr each). Müller et al. go to 20 levels; here, with a
  // region's records from one frame's first waves, deeper leaves fitted the few records that
  // found a light and missed it from the rest of the region (a floor under a small emitter,
  // BSDF sampling alone: noise 0.51 at 6 levels, 0.34 at 4, 0.67 unguided).
  int direction_depth = 4;
  int space_depth = 30;
};

class PathGuide {
 public:
  // `bounds`: the scene's; `brightness`: a radiance typical of its lights, which sets the
  // fixed point's unit (2^-24 of it) and the largest record (2^16 of it).
  PathGuide(const Bounds3& bounds, float brightness, const PathGuideParams& params = {});

  // What the finished rounds learnt (read while rendering, never changed during a wave).
  int rounds() const { return rounds_; }
  // The region of p to sample from, -1 where nothing has been learnt yet.
  int region(const vec3& p) const;
  // A unit direction from the region's distribution and its density per solid angle.
  vec3 sample(int region, const vec2& u, float& pdf) const;
  float pdf(int region, const vec3& wi) const;
  std::size_t regions() const { return sampled_.size(); }

  // Learning: records that `value` (incident radiance over the direction's sampling density)
  // arrived at p from wi. From any thread during a wave.
  void record(const vec3& p, const vec3& wi, float value);

  // The round's statistics (for the ranks to add up) and setting them.
  std::vector<std::uint64_t> statistics() const;
  void set_statistics(const std::vector<std::uint64_t>& stats);
  // Ends the round of a wave of `wave_spp` samples per pixel: its records become the
  // distribution sampled from, the structure is refined and the records cleared.
  void finish_round(int wave_spp);

 private:
  struct Learnt {
    SpaceTree space;
    std::vector<DirectionTree> directions;  // per region
  };
  void clear_records();
  PathGuideParams params_;
  double unit_, largest_;  // of the fixed point
  int rounds_ = 0;
  Learnt sampling_, learning_;
  std::vector<char> sampled_;  // per sampling region: it has energy to sample from
  // Per learning region: its count of records, then its direction nodes' sums; offsets_[r].
  std::vector<std::size_t> offsets_;
  std::unique_ptr<std::atomic<std::uint64_t>[]> records_;
  std::size_t record_count_ = 0;
};

}  // namespace tessera
