// The Sobol sequence in base 2 (its first three dimensions) and hash-based Owen scrambling
// (Burley 2020, "Practical Hash-based Owen Scrambling"; the hash is pbrt-v4's
// FastOwenScrambler). Pure functions of their arguments: no tables to share between threads.
#pragma once

#include <array>
#include <cstdint>

namespace tessera {

inline std::uint32_t reverse_bits(std::uint32_t v) {
  v = ((v >> 1) & 0x55555555u) | ((v & 0x55555555u) << 1);
  v = ((v >> 2) & 0x33333333u) | ((v & 0x33333333u) << 2);
  v = ((v >> 4) & 0x0f0f0f0fu) | ((v & 0x0f0f0f0fu) << 4);
  v = ((v >> 8) & 0x00ff00ffu) | ((v & 0x00ff00ffu) << 8);
  return (v >> 16) | (v << 16);
}

// A random nested uniform scramble of the 32 binary digits of v/2^32: digit k is flipped by
// a hash of the digits above it only (the Laine-Karras property, on reversed bits), so every
// elementary interval is mapped onto another of the same size. Applied to a sample index it
// shuffles each aligned block of 2^k indices onto another aligned block.
inline std::uint32_t owen_scramble(std::uint32_t v, std::uint32_t seed) {
  v = reverse_bits(v);
  v ^= v * 0x3d20adeau;
  v += seed;
  v *= (seed >> 16) | 1u;
  v ^= v * 0x05526c56u;
  v ^= v * 0x53a22864u;
  return reverse_bits(v);
}

constexpr int kSobolDimensions = 3;

// Generator matrix columns of dimensions 0..2 (Joe and Kuo's primitive polynomials x + 1
// and x^2 + x + 1 for dimensions 1 and 2; dimension 0 is van der Corput), 32 bits each.
struct SobolMatrices {
  std::array<std::array<std::uint32_t, 32>, kSobolDimensions> columns{};

  constexpr SobolMatrices() {
    for (int k = 0; k < 32; ++k) columns[0][k] = 1u << (31 - k);
    // m_k by the recurrence m_k = 2 a_1 m_{k-1} ^ ... ^ 2^s m_{k-s} ^ m_{k-s}, v_k = m_k 2^(32-k).
    std::uint32_t m1[32] = {1}, m2[32] = {1, 3};
    for (int k = 1; k < 32; ++k) m1[k] = (m1[k - 1] << 1) ^ m1[k - 1];  // s = 1
    for (int k = 2; k < 32; ++k) m2[k] = (m2[k - 1] << 1) ^ (m2[k - 2] << 2) ^ m2[k - 2];  // s = 2, a_1 = 1
    for (int k = 0; k < 32; ++k) {
      columns[1][k] = m1[k] << (31 - k);
      columns[2][k] = m2[k] << (31 - k);
    }
  }
};

inline constexpr SobolMatrices kSobolMatrices{};

// Dimension `dim` (< kSobolDimensions) of Sobol point `index`, as 32 bits of a fraction.
inline std::uint32_t sobol_bits(std::uint32_t index, int dim) {
  std::uint32_t v = 0;
  for (int k = 0; index; index >>= 1, ++k)
    if (index & 1u) v ^= kSobolMatrices.columns[dim][k];
  return v;
}

// 32 bits of a fraction as a float in [0, 1): the top 24 bits, so exactly below 1.
inline float bits_to_unit_float(std::uint32_t bits) { return static_cast<float>(bits >> 8) * 0x1.0p-24f; }

}  // namespace tessera
