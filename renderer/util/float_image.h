// Float pixels of a decoded image file: what image I/O hands the renderer (an environment
// map), which reads no file format itself.
#pragma once

#include <vector>

namespace tessera {

struct FloatImage {
  int width = 0, height = 0, channels = 0;
  std::vector<float> pixels;  // row-major, top row first, `channels` per pixel
};

}  // namespace tessera
