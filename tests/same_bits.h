// Bit-for-bit comparison of films and frames: what determinism and resume tests assert.
#pragma once

#include <cstring>
#include <vector>

#include "renderer/film/film.h"

namespace tessera::test {

template <typename T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// Every sum, count and flag of the two films.
void expect_same_film(const FilmState& a, const FilmState& b);

// Every layer of the two frames (imageio/exr_layers.h) and their per-pixel counts.
void expect_same_image(const FrameImage& a, const FrameImage& b);

}  // namespace tessera::test
