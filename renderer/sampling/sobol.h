// The Sobol sequence in base 2 (its first three dimensions) and hash-based Owen scrambling
// (Burley 2020, "Practical Hash-based Owen Scrambling"; the hash is pbrt-v4's
// FastOwenScrambler). Pure functions of their arguments: no tables to share between threads.
#pragma once

#include <array>
#include <cstdint>

namespace tessera {

constexpr std::uint32_t reverse_bits_constexpr(std::uint32_t v) {
  std::uint32_t r = 0;
  for (int k = 0; k < 32; ++k) r |= ((v >> k) & 1u) << (31 - k);
  return r;
}

inline std::uint32_t reverse_bits(std::uint32_t v) {
  v = ((v >> 1) & 0x55555555u) | ((v & 0x55555555u) << 1);
  v = ((v >> 2) & 0x33333333u) | ((v & 0x33333333u) << 2);
  v = ((v >> 4) & 0x0f0f0f0fu) | ((v & 0x0f0f0f0fu) << 4);
  v = ((v >> 8) & 0x00ff00ffu) | ((v & 0x00ff00ffu) << 8);
  return (v >> 16) | (v << 16);
}

// The Laine-Karras permutation (pbrt-v4's FastOwenScrambler hash): bit k of the result
// depends on bits 0..k of v only. On bit-reversed values it is a nested uniform (Owen)
// scramble.
inline std::uint32_t laine_karras(std::uint32_t v, std::uint32_t seed) {
  v ^= v * 0x3d20adeau;
  v += seed;
  v *= (seed >> 16) | 1u;
  v ^= v * 0x05526c56u;
  v ^= v * 0x53a22864u;
  return v;
}

// A random nested uniform scramble of the 32 binary digits of v/2^32: digit k is flipped by
// a hash of the digits above it only, so every elementary interval is mapped onto another of
// the same size. Applied to a sample index it shuffles each aligned block of 2^k indices onto
// another aligned block.
inline std::uint32_t owen_scramble(std::uint32_t v, std::uint32_t seed) {
  return reverse_bits(laine_karras(reverse_bits(v), seed));
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

// The matrices in bit-reversed form, a byte at a time: entry [d][b][v] is the XOR of the
// bit-reversed columns 31 - (8b + k) of dimension d over the bits k of v. It maps a
// bit-reversed index to the bit-reversed Sobol value, which is the form the scrambles work
// in, so neither needs reversing: four loads per dimension instead of a loop over 32 bits
// and two bit reversals, which together cost more than a cheap ray.
struct SobolReversedTables {
  std::array<std::array<std::array<std::uint32_t, 256>, 4>, kSobolDimensions> xor_of{};

  constexpr SobolReversedTables() {
    constexpr SobolMatrices m{};
    for (int d = 0; d < kSobolDimensions; ++d)
      for (int b = 0; b < 4; ++b)
        for (int v = 0; v < 256; ++v) {
          std::uint32_t x = 0;
          for (int k = 0; k < 8; ++k)
            if (v & (1 << k)) x ^= reverse_bits_constexpr(m.columns[d][31 - (8 * b + k)]);
          xor_of[d][b][v] = x;
        }
  }
};

inline constexpr SobolReversedTables kSobolReversedTables{};

// The bit-reversed value of dimension `dim` of the Sobol point whose index is
// reverse_bits(reversed_index).
inline std::uint32_t reversed_sobol(std::uint32_t reversed_index, int dim) {
  const auto& t = kSobolReversedTables.xor_of[dim];
  return t[0][reversed_index & 0xffu] ^ t[1][(reversed_index >> 8) & 0xffu] ^ t[2][(reversed_index >> 16) & 0xffu] ^
         t[3][reversed_index >> 24];
}

// Dimension `dim` (< kSobolDimensions) of Sobol point `index`, as 32 bits of a fraction.
inline std::uint32_t sobol_bits(std::uint32_t index, int dim) {
  return reverse_bits(reversed_sobol(reverse_bits(index), dim));
}

// 32 bits of a fraction as a float in [0, 1): the top 24 bits, so exactly below 1.
inline float bits_to_unit_float(std::uint32_t bits) { return static_cast<float>(bits >> 8) * 0x1.0p-24f; }

// The bits of each byte in reverse order.
struct ReversedBytes {
  std::array<std::uint8_t, 256> of{};
  constexpr ReversedBytes() {
    for (int v = 0; v < 256; ++v) of[v] = static_cast<std::uint8_t>(reverse_bits_constexpr(static_cast<std::uint32_t>(v)) >> 24);
  }
};
inline constexpr ReversedBytes kReversedBytes{};

// bits_to_unit_float(reverse_bits(v)): the top 24 bits of the reversal are v's low 24 bits
// reversed, three byte lookups instead of a whole 32-bit reversal.
inline float reversed_bits_to_unit_float(std::uint32_t v) {
  const auto& r = kReversedBytes.of;
  const std::uint32_t top = (std::uint32_t{r[v & 0xffu]} << 16) | (std::uint32_t{r[(v >> 8) & 0xffu]} << 8) | r[(v >> 16) & 0xffu];
  return static_cast<float>(top) * 0x1.0p-24f;
}

// Dimension `dim` of the point whose index is `sample` Owen-scrambled with `index_seed`,
// Owen-scrambled with `value_seed`, as a float in [0, 1): owen_scramble(sobol_bits(
// owen_scramble(sample, index_seed), dim), value_seed), with the reversals that cancel left
// out; the argument is laine_karras(reverse_bits(sample), index_seed).
inline float scrambled_sobol_float(std::uint32_t shuffled_reversed_index, int dim, std::uint32_t value_seed) {
  return reversed_bits_to_unit_float(laine_karras(reversed_sobol(shuffled_reversed_index, dim), value_seed));
}

}  // namespace tessera
