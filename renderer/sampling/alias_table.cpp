#include "renderer/sampling/alias_table.h"

#include <cmath>

namespace tessera {

AliasTable::AliasTable(const std::vector<double>& weights) {
  double total = 0.0;
  for (double w : weights) total += std::isfinite(w) && w > 0.0 ? w : 0.0;
  const std::size_t n = weights.size();
  if (!(total > 0.0) || !std::isfinite(total)) return;
  columns_ = static_cast<float>(n);
  below_end_ = std::nextafter(columns_, 0.0f);
  // Each item's weight in columns of height 1: under 1 it needs an alias to fill its column,
  // over 1 it gives to others'. Lists in index order, so the table is the same on every run.
  std::vector<double> scaled(n);
  std::vector<std::uint32_t> small, large;
  pmf_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double w = std::isfinite(weights[i]) && weights[i] > 0.0 ? weights[i] : 0.0;
    pmf_[i] = static_cast<float>(w / total);
    scaled[i] = w / total * static_cast<double>(n);
    (scaled[i] < 1.0 ? small : large).push_back(static_cast<std::uint32_t>(i));
  }
  entries_.resize(n);
  while (!small.empty() && !large.empty()) {
    const std::uint32_t s = small.back(), l = large.back();
    small.pop_back();
    entries_[s] = {static_cast<float>(scaled[s]), l};
    scaled[l] -= 1.0 - scaled[s];
    if (scaled[l] < 1.0) {
      large.pop_back();
      small.push_back(l);
    }
  }
  // What is left fills its own column (exactly 1 but for rounding).
  for (std::uint32_t i : small) entries_[i] = {1.0f, i};
  for (std::uint32_t i : large) entries_[i] = {1.0f, i};
}

std::vector<double> AliasTable::probabilities() const {
  std::vector<double> p(entries_.size(), 0.0);
  const double column = 1.0 / static_cast<double>(entries_.size());
  for (std::size_t k = 0; k < entries_.size(); ++k) {
    p[k] += column * entries_[k].keep;
    p[entries_[k].alias] += column * (1.0 - entries_[k].keep);
  }
  return p;
}

}  // namespace tessera
