// The film: per-pixel sums of radiance samples (in double, so a million samples still
// add exactly enough) and of the first-hit outputs, resolved into float images. Its whole
// state is a FilmState, which a checkpoint stores and --resume restores bit for bit.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
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
  std::vector<float> noisy_rgb;  // 3 per pixel, in a denoised frame: the beauty before denoising
  // Further channels written as they are, 1 float per pixel each (a denoised frame carries
  // its input's half buffers and sample counts over).
  std::vector<std::pair<std::string, std::vector<float>>> extra_channels;
};

// Everything the film has summed, per pixel, row-major. The AOV vectors are empty unless
// selected. dropped counts the non-finite samples left out of the sums.
struct FilmState {
  int width = 0, height = 0;
  AovSelection aovs;
  std::vector<glm::dvec3> radiance;
  std::vector<vec3> albedo, normal;
  std::vector<float> depth;
  std::vector<std::uint32_t> samples, hits;
  std::uint64_t dropped = 0;

  static FilmState empty(int width, int height, AovSelection aovs);
  std::size_t pixel_count() const { return samples.size(); }
};

class Film {
 public:
  Film(int width, int height, AovSelection aovs);
  explicit Film(FilmState state);  // continues from a checkpoint

  int width() const { return state_.width; }
  int height() const { return state_.height; }

  // Sums over `samples` samples of one pixel, added by the only thread that owns the
  // pixel's tile. Each pixel keeps its own sample count, so a render stopped between
  // tiles is still a complete image, every pixel the mean of the samples it got.
  void add(int x, int y, std::uint32_t samples, const glm::dvec3& radiance_sum,
           const vec3& albedo_sum, const vec3& normal_sum, float depth_sum, std::uint32_t hits);

  std::uint32_t samples(int x, int y) const {
    return state_.samples[static_cast<std::size_t>(y) * state_.width + x];
  }
  std::uint32_t min_samples() const;
  FrameImage resolve() const;

  void set_dropped(std::uint64_t dropped) { state_.dropped = dropped; }
  const FilmState& state() const { return state_; }
  FilmState take_state() { return std::move(state_); }

 private:
  FilmState state_;
};

}  // namespace tessera
