// Distribution1D's guided search against the definition it must keep: the first bin whose
// cdf exceeds u, found by a plain binary search over the whole cdf (a second method), for u
// on every bin boundary, just below and above it, at random, and outside [0, 1).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "renderer/sampling/distribution.h"
#include "tests/uneven_weights.h"

namespace tessera {
namespace {

// The cumulative sums of the clamped weights, normalised, the last exactly 1.
std::vector<float> cdf_of(const std::vector<double>& w) {
  double total = 0.0;
  for (double x : w) total += std::max(x, 0.0);
  std::vector<float> cdf(w.size());
  double running = 0.0;
  for (std::size_t i = 0; i < w.size(); ++i) running += std::max(w[i], 0.0), cdf[i] = static_cast<float>(running / total);
  cdf.back() = 1.0f;
  return cdf;
}

// What sample() must return: upper_bound over the cumulative sums, clamped to the last bin.
std::size_t by_definition(const std::vector<float>& cdf, float u) {
  const std::size_t i = std::upper_bound(cdf.begin(), cdf.end(), u) - cdf.begin();
  return std::min(i, cdf.size() - 1);
}

TEST(Distribution1D, GuidedSearchFindsTheSameBinAsABinarySearch) {
  for (std::size_t n : {1u, 7u, 64u, 65u, 1000u, 46000u}) {
    const std::vector<double> w = test::uneven_weights(n, static_cast<unsigned>(n));
    const Distribution1D d(w);
    const std::vector<float> cdf = cdf_of(w);
    std::vector<float> us = {0.0f, 1.0f, -0.5f, 2.0f, 0.99999994f, std::numeric_limits<float>::infinity(),
                             std::numeric_limits<float>::quiet_NaN()};
    double running = 0.0, total = 0.0;
    for (double x : w) total += x;
    for (double x : w) {  // every boundary, and the floats on either side of it
      running += x;
      const float b = static_cast<float>(running / total);
      us.insert(us.end(), {b, std::nextafter(b, 0.0f), std::nextafter(b, 2.0f)});
    }
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    for (int i = 0; i < 20000; ++i) us.push_back(uniform(rng));
    for (float u : us) ASSERT_EQ(d.sample(u), by_definition(cdf, u)) << "n " << n << ", u " << u;
  }
}

TEST(Distribution1D, ChoosesBinsInProportionToTheirWeights) {
  const std::vector<double> w = test::uneven_weights(4096, 3);
  const Distribution1D d(w);
  std::vector<int> hits(w.size(), 0);
  const int n = 1 << 20;
  for (int i = 0; i < n; ++i) ++hits[d.sample((i + 0.5f) / n)];  // stratified: counts within 1 of n pmf
  for (std::size_t i = 0; i < w.size(); ++i) EXPECT_NEAR(hits[i], n * w[i] / d.total(), 1.5) << "bin " << i;
}

}  // namespace
}  // namespace tessera
