// What a rank rendered in a wave, as bytes for the other ranks: the tiles it took and the
// state of their pixels after the wave (every sum, count and flag of FilmState). Each pixel
// belongs to one tile and each tile to one rank, and every rank starts the wave with the same
// film, so copying those pixels over leaves every rank with the film a single process makes,
// bit for bit.
#pragma once

#include <cstddef>
#include <vector>

#include "renderer/film/film.h"
#include "renderer/parallel/tile_scheduler.h"

namespace tessera {

std::vector<char> pack_tiles(const FilmState& film, const std::vector<Tile>& tiles, const std::vector<std::size_t>& taken);
// Copies the pixels `bytes` carries into `film`; the tiles are the same plan's.
void unpack_tiles(FilmState& film, const std::vector<Tile>& tiles, const std::vector<char>& bytes);

}  // namespace tessera
