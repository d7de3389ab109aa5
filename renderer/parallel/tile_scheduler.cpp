#include "renderer/parallel/tile_scheduler.h"

#include <algorithm>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

namespace tessera {

std::vector<Tile> make_tiles(int width, int height, int tile_size) {
  std::vector<Tile> tiles;
  for (int y = 0; y < height; y += tile_size)
    for (int x = 0; x < width; x += tile_size)
      tiles.push_back({x, y, std::min(x + tile_size, width), std::min(y + tile_size, height)});
  return tiles;
}

std::vector<SampleWave> make_sample_waves(int spp, int max_wave) {
  std::vector<SampleWave> waves;
  int size = 1;
  for (int begin = 0; begin < spp;) {
    const int end = std::min(spp, begin + size);
    waves.push_back({begin, end});
    begin = end;
    size = std::min(2 * size, max_wave);
  }
  return waves;
}

void run_tiles_dynamic(std::size_t count, const std::function<void(std::size_t)>& body) {
  // simple_partitioner with grain 1: every tile is a separate task.
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, count, 1),
      [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) body(i);
      },
      tbb::simple_partitioner());
}

}  // namespace tessera
