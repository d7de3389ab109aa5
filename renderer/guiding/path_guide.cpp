#include "renderer/guiding/path_guide.h"

#include <cmath>

namespace tessera {

namespace {
constexpr float kInvFourPi = 0.25f * kInvPi;  // the square's density per solid angle
}

PathGuide::PathGuide(const Bounds3& bounds, float brightness, const PathGuideParams& params) : params_(params) {
  Bounds3 box = bounds;
  if (box.empty()) box = Bounds3{vec3(-1.0f), vec3(1.0f)};
  // A little larger, and cubical enough that a flat scene's regions are not slivers.
  const vec3 d = box.diagonal();
  const float size = std::max(std::max(d.x, std::max(d.y, d.z)), 1e-6f);
  box.lo -= vec3(0.01f * size), box.hi += vec3(0.01f * size);
  const double b = std::isfinite(brightness) && brightness > 0.0f ? brightness : 1.0;
  unit_ = b * std::ldexp(1.0, -24);
  largest_ = b * std::ldexp(1.0, 16);
  sampling_.space = learning_.space = SpaceTree(box);
  sampling_.directions.assign(1, DirectionTree());
  // The first round learns in 16 directions alike (a single node would learn nothing of where
  // light comes from).
  DirectionTree uniform;
  uniform.set_energy({1.0});
  learning_.directions.assign(1, uniform.refined(0.01, 2));
  sampled_.assign(1, 0);
  clear_records();
}

void PathGuide::clear_records() {
  offsets_.resize(learning_.directions.size() + 1);
  std::size_t n = 0;
  for (std::size_t r = 0; r < learning_.directions.size(); ++r) offsets_[r] = n, n += 1 + learning_.directions[r].size();
  offsets_.back() = n;
  records_ = std::make_unique<std::atomic<std::uint64_t>[]>(n);
  for (std::size_t i = 0; i < n; ++i) records_[i].store(0, std::memory_order_relaxed);
  record_count_ = n;
}

int PathGuide::region(const vec3& p) const {
  if (rounds_ == 0) return -1;
  const std::uint32_t r = sampling_.space.region_of(p);
  return sampled_[r] ? static_cast<int>(r) : -1;
}

vec3 PathGuide::sample(int region, const vec2& u, float& pdf) const {
  const vec2 p = sampling_.directions[region].sample(u, pdf);
  pdf *= kInvFourPi;
  return square_to_direction(p);
}

float PathGuide::pdf(int region, const vec3& wi) const {
  return sampling_.directions[region].pdf(direction_to_square(wi)) * kInvFourPi;
}

void PathGuide::record(const vec3& p, const vec3& wi, float value) {
  if (!(value >= 0.0f)) return;  // NaN or negative: nothing learnt
  const std::uint32_t r = learning_.space.region_of(p);
  const std::uint32_t leaf = learning_.directions[r].leaf_of(direction_to_square(wi));
  const double v = std::min(static_cast<double>(value), largest_);
  const auto q = static_cast<std::uint64_t>(std::llround(v / unit_));
  records_[offsets_[r]].fetch_add(1, std::memory_order_relaxed);
  if (q > 0) records_[offsets_[r] + 1 + leaf].fetch_add(q, std::memory_order_relaxed);
}

std::vector<std::uint64_t> PathGuide::statistics() const {
  std::vector<std::uint64_t> out(record_count_);
  for (std::size_t i = 0; i < record_count_; ++i) out[i] = records_[i].load(std::memory_order_relaxed);
  return out;
}

void PathGuide::set_statistics(const std::vector<std::uint64_t>& stats) {
  for (std::size_t i = 0; i < record_count_ && i < stats.size(); ++i) records_[i].store(stats[i], std::memory_order_relaxed);
}

void PathGuide::finish_round(int wave_spp) {
  const std::size_t n = learning_.directions.size();
  std::vector<std::uint64_t> counts(n);
  sampled_.assign(n, 0);
  for (std::size_t r = 0; r < n; ++r) {
    DirectionTree& tree = learning_.directions[r];
    counts[r] = records_[offsets_[r]].load(std::memory_order_relaxed);
    std::vector<double> energy(tree.size());
    for (std::size_t k = 0; k < tree.size(); ++k)
      energy[k] = static_cast<double>(records_[offsets_[r] + 1 + k].load(std::memory_order_relaxed)) * unit_;
    tree.set_energy(energy);
    sampled_[r] = tree.total() > 0.0;
  }
  sampling_ = learning_;
  std::vector<std::uint32_t> from;
  learning_.space = sampling_.space.split(counts, params_.split_records * std::sqrt(static_cast<double>(wave_spp)),
                                          from, params_.space_depth);
  learning_.directions.clear();
  for (std::uint32_t r : from)
    learning_.directions.push_back(
        sampling_.directions[r].refined(params_.direction_fraction, params_.direction_depth));
  ++rounds_;
  clear_records();
}

}  // namespace tessera
