// The per-sample random streams: uniform, independent across dimensions and pixels, and
// a pure function of (pixel, sample, dimension, seed).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "renderer/sampler.h"

namespace tessera {
namespace {

TEST(SampleStream, IsAPureFunctionOfItsKey) {
  SampleStream a(3, 5, 7, 11), b(3, 5, 7, 11);
  for (int d = 0; d < 64; ++d) ASSERT_EQ(a.next(), b.next());
  EXPECT_NE(SampleStream(3, 5, 7, 11).get(0), SampleStream(5, 3, 7, 11).get(0));  // x and y not interchangeable
  EXPECT_NE(SampleStream(3, 5, 7, 11).get(0), SampleStream(3, 5, 8, 11).get(0));
  EXPECT_NE(SampleStream(3, 5, 7, 11).get(0), SampleStream(3, 5, 7, 12).get(0));
}

// Pearson chi-square over 64 equal bins for 2^18 values of one dimension across pixels,
// and over an 8x8 grid of consecutive dimension pairs (independence). With 63 degrees of
// freedom the 99.9th percentile of chi-square is 103.4.
TEST(SampleStream, IsUniformAndPairwiseIndependent) {
  constexpr int kBins = 64, kN = 1 << 18;
  for (int dim : {0, 1, 7, 40}) {
    std::vector<int> bins(kBins, 0);
    std::vector<int> grid(kBins, 0);
    for (int i = 0; i < kN; ++i) {
      SampleStream s(i % 512, i / 512, 3, 99);
      const float u = s.get(dim), v = s.get(dim + 1);
      ASSERT_GE(u, 0.0f);
      ASSERT_LT(u, 1.0f);
      ++bins[static_cast<int>(u * kBins)];
      ++grid[static_cast<int>(u * 8) * 8 + static_cast<int>(v * 8)];
    }
    auto chi2 = [&](const std::vector<int>& counts) {
      const double expected = static_cast<double>(kN) / kBins;
      double c = 0;
      for (int n : counts) c += (n - expected) * (n - expected) / expected;
      return c;
    };
    EXPECT_LT(chi2(bins), 103.4) << "dimension " << dim;
    EXPECT_LT(chi2(grid), 103.4) << "dimensions " << dim << "," << dim + 1;
  }
}

}  // namespace
}  // namespace tessera
