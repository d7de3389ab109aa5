// The alias table against the weights it was built from: its probabilities, read back from
// the table (a second method: each column's kept share plus the shares aliased to it), equal
// weight / total; draws follow them (Pearson's chi-square); an item of weight 0 is never drawn.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "renderer/sampling/alias_table.h"
#include "tests/uneven_weights.h"

namespace tessera {
namespace {

double sum(const std::vector<double>& w) {
  double total = 0.0;
  for (double x : w) total += x;
  return total;
}

TEST(AliasTable, ItsProbabilitiesAreTheWeightsShares) {
  for (std::size_t n : {1u, 2u, 7u, 1000u, 46000u}) {
    const std::vector<double> w = test::uneven_weights(n, static_cast<unsigned>(n) + 1);
    const double total = sum(w);
    const AliasTable table(w);
    const std::vector<double> p = table.probabilities();
    ASSERT_EQ(p.size(), total > 0.0 ? n : 0);  // n = 1 draws weight 0: an empty table
    if (p.empty()) continue;
    for (std::size_t i = 0; i < n; ++i) {
      ASSERT_NEAR(p[i], w[i] / total, 1e-7 * (w[i] / total) + 1e-12) << "n " << n << ", item " << i;
      ASSERT_EQ(table.pmf(i), static_cast<float>(w[i] / total)) << "n " << n << ", item " << i;
    }
  }
}

TEST(AliasTable, DrawsFollowTheWeights) {
  const std::vector<double> w = test::uneven_weights(4096, 3);
  const double total = sum(w);
  const AliasTable table(w);
  std::vector<double> hits(w.size(), 0.0);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  const int draws = 1 << 22;
  for (int k = 0; k < draws; ++k) hits[table.sample(uniform(rng))] += 1.0;
  double chi2 = 0.0;
  int dof = -1;
  for (std::size_t i = 0; i < w.size(); ++i) {
    if (w[i] == 0.0) {
      ASSERT_EQ(hits[i], 0.0) << "item " << i << " has weight 0";
      continue;
    }
    const double expected = draws * w[i] / total;
    chi2 += (hits[i] - expected) * (hits[i] - expected) / expected;
    ++dof;
  }
  // Mean dof, standard deviation sqrt(2 dof): five of them is p < 1e-6.
  EXPECT_LT(chi2, dof + 5.0 * std::sqrt(2.0 * dof)) << "dof " << dof;
}

TEST(AliasTable, EveryColumnAndItsEdgesGiveAnItemOfWeight) {
  const std::vector<double> w = {0.0, 3.0, 0.0, 1.0, 0.0, 0.0, 4.0};
  const AliasTable table(w);
  const float n = static_cast<float>(w.size());
  std::vector<float> us = {0.0f, 0.99999994f, 1.0f, 2.0f, -1.0f, std::numeric_limits<float>::quiet_NaN(),
                           std::numeric_limits<float>::infinity()};
  for (int i = 0; i <= 7; ++i)
    for (float edge : {i / n, std::nextafter(i / n, 0.0f), std::nextafter(i / n, 1.0f)}) us.push_back(edge);
  for (float u : us) {
    const std::size_t i = table.sample(u);
    ASSERT_LT(i, w.size()) << "u " << u;
    EXPECT_GT(w[i], 0.0) << "u " << u << " drew item " << i;
  }
}

TEST(AliasTable, NoPositiveWeightLeavesItEmpty) {
  EXPECT_TRUE(AliasTable(std::vector<double>{}).empty());
  EXPECT_TRUE(AliasTable(std::vector<double>{0.0, -1.0, std::numeric_limits<double>::quiet_NaN()}).empty());
  EXPECT_FALSE(AliasTable(std::vector<double>{0.0, 2.0}).empty());
}

}  // namespace
}  // namespace tessera
