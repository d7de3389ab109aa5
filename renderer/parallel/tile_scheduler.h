// Splits the image into tiles and the samples into waves, and runs tiles on all threads.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

namespace tessera {

struct Tile {
  int x0, y0, x1, y1;  // pixel rectangle [x0, x1) x [y0, y1)
  int pixel_count() const { return (x1 - x0) * (y1 - y0); }
};

std::vector<Tile> make_tiles(int width, int height, int tile_size);

// Sample waves over the whole image, as pbrt-v4 takes them: 1, 2, 4, ... samples per pixel
// per wave, at most `max_wave` at once, together exactly `spp`. Each entry is [begin, end).
struct SampleWave {
  int begin, end;
};
std::vector<SampleWave> make_sample_waves(int spp, int max_wave = 64);

// Runs body(tile index) once for each of `count` tiles on the current TBB arena. Tiles are
// handed out dynamically (each tile its own task, work stealing), so no thread sits idle
// while another still has a queue of work.
void run_tiles_dynamic(std::size_t count, const std::function<void(std::size_t)>& body);

}  // namespace tessera
