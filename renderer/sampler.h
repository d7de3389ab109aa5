// Random numbers that depend only on (pixel, sample index, dimension, seed), never on the
// thread, tile or order of work: the image is identical bit for bit however it is split.
#pragma once

#include <cstdint>

#include "renderer/math.h"

namespace tessera {

// SplitMix64's finalizer: a bijective 64-bit mix with full avalanche.
inline std::uint64_t mix64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// The random stream of one camera sample. Dimension d of the stream is a hash of the
// stream key and d, so streams never overlap and skipping dimensions costs nothing.
class SampleStream {
 public:
  SampleStream(std::uint32_t px, std::uint32_t py, std::uint32_t sample, std::uint32_t seed)
      : key_(mix64(mix64((std::uint64_t(seed) << 32) | sample) ^
                   ((std::uint64_t(py) << 32) | px))) {}

  float get(std::uint32_t dimension) const {
    const std::uint64_t bits = mix64(key_ + 0x9e3779b97f4a7c15ULL * (dimension + 1));
    return static_cast<float>(bits >> 40) * 0x1.0p-24f;  // 24 bits: exactly in [0, 1)
  }
  float next() { return get(dimension_++); }
  vec2 next2() {
    const float a = next();
    return {a, next()};
  }

 private:
  std::uint64_t key_;
  std::uint32_t dimension_ = 0;
};

}  // namespace tessera
