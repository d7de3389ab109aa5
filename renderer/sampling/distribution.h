// Sampling in proportion to a tabulated non-negative function by inverting its cdf: the
// piecewise-constant densities of an environment image's rows and columns, where u
// falls inside the bin matters (a discrete choice alone, lights by power: alias_table.h).
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

namespace tessera {

class Distribution1D {
 public:
  Distribution1D() = default;
  explicit Distribution1D(std::vector<double> weights) : pmf_(weights.size()), cdf_(weights.size()) {
    double total = 0.0;
    for (double w : weights) total += w > 0.0 ? w : 0.0;
    total_ = total;
    double running = 0.0;
    for (std::size_t i = 0; i < weights.size(); ++i) {
      const double w = weights[i] > 0.0 ? weights[i] : 0.0;
      pmf_[i] = total > 0.0 ? static_cast<float>(w / total) : 0.0f;
      running += w;
      cdf_[i] = total > 0.0 ? static_cast<float>(running / total) : 0.0f;
    }
    if (!cdf_.empty() && total > 0.0) cdf_.back() = 1.0f;
    build_guide();
  }

  bool empty() const { return !(total_ > 0.0); }
  std::size_t size() const { return pmf_.size(); }
  double total() const { return total_; }  // sum of the weights
  float pmf(std::size_t i) const { return pmf_[i]; }

  // The bin with cdf[i-1] <= u < cdf[i]; `offset` is where u falls inside it, in [0,1).
  std::size_t sample(float u, float* offset = nullptr) const {
    const std::size_t i = std::min<std::size_t>(first_above(u), cdf_.size() - 1);
    if (offset) {
      const float lo = i > 0 ? cdf_[i - 1] : 0.0f;
      *offset = pmf_[i] > 0.0f ? std::clamp((u - lo) / pmf_[i], 0.0f, 0.99999994f) : 0.0f;
    }
    return i;
  }

 private:
  // Bins per guide entry: the guide narrows a binary search over a large cdf (each step a
  // cache miss) to about this many bins.
  static constexpr std::size_t kBinsPerGuide = 8;

  // guide_[k]: the first bin whose cdf exceeds k / guide_.size().
  void build_guide() {
    if (cdf_.size() < 8 * kBinsPerGuide || !(total_ > 0.0)) return;
    guide_.resize(cdf_.size() / kBinsPerGuide);
    guide_count_ = static_cast<float>(guide_.size());
    for (std::size_t k = 0; k < guide_.size(); ++k) {
      const float t = static_cast<float>(static_cast<double>(k) / guide_.size());
      guide_[k] = static_cast<std::uint32_t>(std::upper_bound(cdf_.begin(), cdf_.end(), t) - cdf_.begin());
    }
  }

  // The first i with cdf[i] > u (cdf.size() when none), exactly as a binary search over the
  // whole cdf finds it: the guide only narrows the range, and a range that may not hold the
  // answer (rounding at a guide boundary, u outside [0, 1), NaN) falls back to the whole.
  std::size_t first_above(float u) const {
    std::size_t lo = 0, hi = cdf_.size();
    if (!guide_.empty()) {
      // In float and int: conversions to and from size_t cost a branch each.
      const float x = u * guide_count_;
      const int last = static_cast<int>(guide_.size()) - 1;
      const std::size_t k = static_cast<std::size_t>(x > 0.0f ? (x < guide_count_ ? static_cast<int>(x) : last) : 0);
      lo = guide_[k];
      hi = k + 1 < guide_.size() ? std::min<std::size_t>(guide_[k + 1] + 1, cdf_.size()) : cdf_.size();
      if ((lo > 0 && !(cdf_[lo - 1] <= u)) || (hi < cdf_.size() && !(cdf_[hi - 1] > u))) lo = 0, hi = cdf_.size();
    }
    return upper_bound(lo, hi, u);
  }

  // std::upper_bound's index in cdf_[lo, hi) without a branch per step to mispredict: the
  // range halves by a conditional move.
  std::size_t upper_bound(std::size_t lo, std::size_t hi, float u) const {
    if (lo == hi) return lo;
    const float* base = cdf_.data() + lo;
    for (std::size_t n = hi - lo; n > 1; n -= n / 2) base += u < base[n / 2] ? 0 : n / 2;
    return static_cast<std::size_t>(base - cdf_.data()) + (u < *base ? 0 : 1);
  }

  std::vector<float> pmf_, cdf_;
  std::vector<std::uint32_t> guide_;
  float guide_count_ = 0.0f;  // guide_.size()
  double total_ = 0.0;
};

}  // namespace tessera
