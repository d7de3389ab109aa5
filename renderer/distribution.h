// Sampling in proportion to a tabulated non-negative function: discrete choices (lights by
// power) and piecewise-constant densities (rows and columns of an environment image).
#pragma once

#include <algorithm>
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
  }

  bool empty() const { return !(total_ > 0.0); }
  std::size_t size() const { return pmf_.size(); }
  double total() const { return total_; }  // sum of the weights
  float pmf(std::size_t i) const { return pmf_[i]; }

  // The bin with cdf[i-1] <= u < cdf[i]; `offset` is where u falls inside it, in [0,1).
  std::size_t sample(float u, float* offset = nullptr) const {
    const std::size_t i =
        std::min<std::size_t>(std::upper_bound(cdf_.begin(), cdf_.end(), u) - cdf_.begin(), cdf_.size() - 1);
    if (offset) {
      const float lo = i > 0 ? cdf_[i - 1] : 0.0f;
      *offset = pmf_[i] > 0.0f ? std::clamp((u - lo) / pmf_[i], 0.0f, 0.99999994f) : 0.0f;
    }
    return i;
  }

 private:
  std::vector<float> pmf_, cdf_;
  double total_ = 0.0;
};

}  // namespace tessera
