#include "renderer/parallel/tile_order.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>

#include "renderer/util/named_enum.h"

namespace tessera {

TileGrid tile_grid(int width, int height, int tile_size) {
  return {(width + tile_size - 1) / tile_size, (height + tile_size - 1) / tile_size};
}

unsigned hilbert_index(unsigned side, unsigned x, unsigned y) {
  // The classic xy2d: at each scale pick the quadrant, then rotate/flip into its frame.
  unsigned d = 0;
  for (unsigned s = side / 2; s > 0; s /= 2) {
    const unsigned rx = (x & s) ? 1 : 0, ry = (y & s) ? 1 : 0;
    d += s * s * ((3 * rx) ^ ry);
    if (ry == 0) {
      if (rx == 1) {
        x = s - 1 - (x & (s - 1));
        y = s - 1 - (y & (s - 1));
      }
      std::swap(x, y);
    }
  }
  return d;
}

namespace {

std::vector<int> hilbert_order(TileGrid g) {
  unsigned side = 1;
  while (side < static_cast<unsigned>(std::max(g.columns, g.rows))) side *= 2;
  std::vector<unsigned> key(static_cast<std::size_t>(g.columns) * g.rows);
  for (int y = 0; y < g.rows; ++y)
    for (int x = 0; x < g.columns; ++x) key[y * g.columns + x] = hilbert_index(side, x, y);
  std::vector<int> order(key.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return key[a] < key[b]; });
  return order;
}

// Walks right 1, down 1, left 2, up 2, right 3, ... from the centre tile, keeping the
// cells inside the grid, until every tile has been visited.
std::vector<int> spiral_order(TileGrid g) {
  const std::size_t total = static_cast<std::size_t>(g.columns) * g.rows;
  std::vector<int> order;
  order.reserve(total);
  int x = (g.columns - 1) / 2, y = (g.rows - 1) / 2;
  const int dx[4] = {1, 0, -1, 0}, dy[4] = {0, 1, 0, -1};
  auto visit = [&] {
    if (x >= 0 && x < g.columns && y >= 0 && y < g.rows) order.push_back(y * g.columns + x);
  };
  visit();
  for (int leg = 0; order.size() < total; ++leg) {
    const int length = leg / 2 + 1;
    for (int step = 0; step < length; ++step) {
      x += dx[leg % 4];
      y += dy[leg % 4];
      visit();
    }
  }
  return order;
}

}  // namespace

std::vector<int> tile_order(TileGrid grid, TileOrder order) {
  if (order == TileOrder::spiral) return spiral_order(grid);
  if (order == TileOrder::hilbert) return hilbert_order(grid);
  std::vector<int> scan(static_cast<std::size_t>(grid.columns) * grid.rows);
  std::iota(scan.begin(), scan.end(), 0);
  return scan;
}

const std::vector<std::string>& tile_order_names() {
  static const std::vector<std::string> names = {"scanline", "spiral", "hilbert"};
  return names;
}

const char* tile_order_name(TileOrder order) { return enum_name(tile_order_names(), order); }

TileOrder parse_tile_order(const std::string& name) { return parse_enum<TileOrder>(tile_order_names(), name, "tile order"); }

}  // namespace tessera
