// The order in which tiles are offered to the threads. It never changes the image (every
// random number depends only on pixel, sample and seed), only which part of the image
// finishes first and how the last tiles of a wave line up.
#pragma once

#include <string>
#include <vector>

#include "renderer/parallel/tile_scheduler.h"

namespace tessera {

enum class TileOrder {
  scanline,  // rows of tiles, top to bottom
  spiral,  // a square spiral from the image centre outwards
  hilbert,  // along a Hilbert curve over the tile grid (neighbours stay close in time)
};

// The tile grid make_tiles builds: `columns` x `rows` tiles, row-major.
struct TileGrid {
  int columns = 0, rows = 0;
};
TileGrid tile_grid(int width, int height, int tile_size);

// A permutation of the row-major tile indices 0 .. columns*rows-1 in the given order.
std::vector<int> tile_order(TileGrid grid, TileOrder order);

// "scanline", "spiral", "hilbert"; parse throws std::invalid_argument for anything else.
const char* tile_order_name(TileOrder order);
TileOrder parse_tile_order(const std::string& name);
const std::vector<std::string>& tile_order_names();

// Position of cell (x, y) along the Hilbert curve filling a side x side square, side a
// power of two.
unsigned hilbert_index(unsigned side, unsigned x, unsigned y);

}  // namespace tessera
