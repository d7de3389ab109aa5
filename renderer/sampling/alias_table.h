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
  float pmf(std::size_t i) const { return pmf_[i]; }  // weight i / the weights' sum

  // u in [0, 1) picks column floor(u n) and, by where u falls inside it, the column's own
  // item or its alias. Never an item of weight 0; u outside [0, 1) is clamped. A float u
  // tells 2^24 columns apart, as a float cdf would: past that, some columns are never drawn.
  std::size_t sample(float u) const {
    float x = u * columns_;
    x = x > 0.0f ? x : 0.0f;  // below 0, or NaN
    x = x < below_end_ ? x : below_end_;
    const int i = static_cast<int>(x);  // a table of 2^31 lights would not fit in memory
    const Entry& e = entries_[static_cast<std::size_t>(i)];
    return x - static_cast<float>(i) < e.keep ? static_cast<std::size_t>(i) : e.alias;
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
  std::vector<float> pmf_;  // apart from the entries: sample() reads those alone
  // The column count and the largest float below it, as floats: the draw stays in float and
  // int (conversions to and from size_t cost a branch each).
  float columns_ = 0.0f, below_end_ = 0.0f;
};

}  // namespace tessera
