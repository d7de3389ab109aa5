// The film: per-pixel sums of radiance samples (in double, so a million samples still
// add exactly enough) and of the first-hit outputs, resolved into float images.
#pragma once

#include <cstdint>
#include <vector>

#include "renderer/math.h"

namespace tessera {

struct AovSelection {
  bool albedo = false, normal = false, depth = false;
  bool any() const { return albedo || normal || depth; }
};

// A finished frame: linear RGB and the requested outputs, row-major, top row first.
struct FrameImage {
  int width = 0, height = 0;
  int samples_per_pixel = 0;  // the fewest any pixel got
  std::vector<float> rgb;  // 3 per pixel
  std::vector<float> albedo, normal;  // 3 per pixel, when requested
  std::vector<float> depth;  // 1 per pixel, when requested; 0 where no sample hit
  std::vector<float> cost;  // 1 per pixel, when requested: CPU seconds spent on the pixel's tile
};

class Film {
 public:
  Film(int width, int height, AovSelection aovs);

  int width() const { return width_; }
  int height() const { return height_; }

  // Sums over `samples` samples of one pixel, added by the only thread that owns the
  // pixel's tile. Each pixel keeps its own sample count, so a render stopped between
  // tiles is still a complete image, every pixel the mean of the samples it got.
  void add(int x, int y, std::uint32_t samples, const glm::dvec3& radiance_sum,
           const vec3& albedo_sum, const vec3& normal_sum, float depth_sum, std::uint32_t hits);

  std::uint32_t min_samples() const;
  FrameImage resolve() const;

 private:
  int width_, height_;
  AovSelection aovs_;
  std::vector<glm::dvec3> radiance_;
  std::vector<vec3> albedo_, normal_;
  std::vector<float> depth_;
  std::vector<std::uint32_t> samples_, hits_;
};

}  // namespace tessera
