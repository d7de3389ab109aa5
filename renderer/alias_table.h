// Choosing among n items in proportion to their weights in constant time: Walker's alias
// method, built by Vose's algorithm. A draw reads one entry, where inverting a cdf reads a
// guide entry and then the cdf, each a cache miss on a large table (DamagedHelmet's 46,000
// emissive triangles: 4% of its render).
#pragma once

#include <cstdint>
#include <vector>

namespace tessera {

class AliasTable {
 public:
  AliasTable() = default;
  // Negative and non-finite weights count as 0; all 0 leaves the table empty.
  explicit AliasTable(const std::vector<double>& weights);

  bool empty() const { return entries_.empty(); }
  std::size_t size() const { return entries_.size(); }

  // u in [0, 1) picks column floor(u n) and, by where u falls inside it, the column's own
  // item or its alias. Never an item of weight 0; u outside [0, 1) is clamped.
  std::size_t sample(float u) const {
    float x = u * static_cast<float>(entries_.size());
    if (!(x > 0.0f)) x = 0.0f;  // below 0, or NaN; past the end, the last column's alias
    const std::size_t last = entries_.size() - 1;
    const std::size_t i = x < static_cast<float>(last) ? static_cast<std::size_t>(x) : last;
    const Entry& e = entries_[i];
    return x - static_cast<float>(i) < e.keep ? i : e.alias;
  }

  // The probability sample() gives each item over u uniform in [0, 1), from the table itself:
  // its own column's share plus the shares of the columns that alias it (tests).
  std::vector<double> probabilities() const;

 private:
  struct Entry {
    float keep;  // the share of the column that stays with its own item
    std::uint32_t alias;
  };
  std::vector<Entry> entries_;
};

}  // namespace tessera
