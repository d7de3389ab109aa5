// Weights like emitters' powers, for the tests of the discrete samplers: a quarter of them
// 0 (dark emitters), a few very heavy (a helmet's glow), the rest in (0.25, 0.98].
#pragma once

#include <random>
#include <vector>

namespace tessera::test {

inline std::vector<double> uneven_weights(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<double> w(n);
  for (double& x : w) {
    const double r = uniform(rng);
    x = r < 0.25 ? 0.0 : r > 0.98 ? 1e4 * r : r;
  }
  return w;
}

}  // namespace tessera::test
