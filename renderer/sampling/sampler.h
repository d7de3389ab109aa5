// The random numbers of one camera sample. Every number is a function of (pixel, sample
// index, draw, seed) alone, never of the thread, tile or order of work: the image is the same
// bit for bit however it is split, and a resumed render continues exactly.
//
// The integrator asks for draws in a fixed order (camera jitter, the lens position with an
// aperture, the shutter time when something moves, then per bounce: light selection and
// point, environment direction, lobe and direction, roulette), each draw 1, 2 or 3 numbers
// meant to be used together.
//   sobol:       each draw is a point of a padded, Owen-scrambled Sobol sequence (pbrt-v4's
//                PaddedSobolSampler, Burley 2020): over a pixel's samples, every 2D draw is a
//                (0,2)-sequence, so each of its elementary intervals holds one point per 2^k
//                samples; the sample order is shuffled (Owen-scrambling the index) and the
//                values scrambled with seeds hashed from the pixel and the draw, so pixels and
//                draws are decorrelated. The third number of a 3D draw (a lobe or light choice)
//                is Sobol's dimension 2 of the same point.
//   independent: every number an independent hash (white noise), for comparison.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "renderer/util/math.h"
#include "renderer/sampling/sobol.h"

namespace tessera {

enum class SamplerKind : std::uint8_t { sobol, independent };

const char* sampler_name(SamplerKind kind);
SamplerKind parse_sampler(const std::string& name);  // throws std::invalid_argument
const std::vector<std::string>& sampler_names();

// SplitMix64's finalizer: a bijective 64-bit mix with full avalanche.
inline std::uint64_t mix64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

class Sampler {
 public:
  Sampler(SamplerKind kind, std::uint32_t px, std::uint32_t py, std::uint32_t sample, std::uint32_t seed)
      : Sampler(kind, pixel_key(kind, px, py, seed), sample) {}
  // What every sample of pixel (px, py) shares: a pixel's samples made together hash it once.
  static std::uint64_t pixel_key(SamplerKind kind, std::uint32_t px, std::uint32_t py, std::uint32_t seed) {
    return mix64(mix64((std::uint64_t(seed) << 32) | kind_tag(kind)) ^ ((std::uint64_t(py) << 32) | px));
  }
  Sampler(SamplerKind kind, std::uint64_t pixel_key, std::uint32_t sample)
      : pixel_key_(pixel_key), sample_(sample), reversed_sample_(reverse_bits(sample)), kind_(kind) {}

  float next() { return draw(1)[0]; }
  vec2 next2() {
    const auto v = draw(2);
    return {v[0], v[1]};
  }
  // next2() of the samplers of one pixel at the same draw (a pixel's camera samples: the
  // first draw), for n <= kTogether of them: what each would return alone, bit for bit. The
  // pixel's hashes are made once, and each step for all the samples before the next, so that
  // the samples' chains of dependent multiplies and lookups overlap.
  static constexpr int kTogether = 16;
  static void next2_of_pixel(Sampler* const* samplers, int n, vec2* out) {
    if (n <= 0) return;
    const Sampler& first = *samplers[0];
    if (first.kind_ == SamplerKind::independent) {
      for (int k = 0; k < n; ++k) out[k] = samplers[k]->next2();
      return;
    }
    for (int k = 0; k < n; ++k) ++samplers[k]->draws_;  // all at first's draw: one pixel, one draw
    const std::uint64_t key = first.draw_key();
    const std::uint64_t more = mix64(key ^ kMoreSeeds);
    std::uint32_t index[kTogether];
    for (int k = 0; k < n; ++k) index[k] = laine_karras(samplers[k]->reversed_sample_, static_cast<std::uint32_t>(key));
    for (int k = 0; k < n; ++k) out[k].x = scrambled_sobol_float(index[k], 0, static_cast<std::uint32_t>(key >> 32));
    for (int k = 0; k < n; ++k) out[k].y = scrambled_sobol_float(index[k], 1, static_cast<std::uint32_t>(more));
  }
  // A 2D point (x, y) and a choice z drawn together.
  vec3 next3() {
    const auto v = draw(3);
    return {v[0], v[1], v[2]};
  }

 private:
  static std::uint64_t kind_tag(SamplerKind kind) { return kind == SamplerKind::sobol ? 0x50b01 : 0; }

  static constexpr std::uint64_t kMoreSeeds = 0x2545f4914f6cdd1dULL;
  // The hash of (pixel, draw): the draw's scramble seeds, shared by the pixel's samples.
  std::uint64_t draw_key() const { return mix64(pixel_key_ + 0x9e3779b97f4a7c15ULL * draws_); }

  std::array<float, 3> draw(int n) {
    ++draws_;
    const std::uint64_t key = draw_key();
    std::array<float, 3> v{};
    if (kind_ == SamplerKind::independent) {
      for (int d = 0; d < n; ++d) {
        const std::uint64_t bits = mix64(key ^ (mix64(sample_) + d));
        v[d] = static_cast<float>(bits >> 40) * 0x1.0p-24f;  // 24 bits: exactly in [0, 1)
      }
      return v;
    }
    // The shuffled index stays bit-reversed: scrambled_sobol_float takes it so. The scrambles'
    // seeds are the key's two halves and, for a second and third number, one more hash of it.
    const std::uint32_t index = laine_karras(reversed_sample_, static_cast<std::uint32_t>(key));
    const std::uint64_t more = n > 1 ? mix64(key ^ kMoreSeeds) : 0;
    const std::uint32_t seeds[3] = {static_cast<std::uint32_t>(key >> 32), static_cast<std::uint32_t>(more),
                                    static_cast<std::uint32_t>(more >> 32)};
    for (int d = 0; d < n; ++d) v[d] = scrambled_sobol_float(index, d, seeds[d]);
    return v;
  }

  std::uint64_t pixel_key_;
  std::uint32_t sample_, reversed_sample_;
  std::uint32_t draws_ = 0;
  SamplerKind kind_;
};

}  // namespace tessera
