// The film: per-pixel sums of radiance samples (in double, so a million samples still
// add exactly enough) and of the first-hit outputs, resolved into float images. Its whole
// state is a FilmState, which a checkpoint stores and --resume restores bit for bit.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "renderer/util/math.h"

namespace tessera {

struct AovSelection {
  bool albedo = false, normal = false, depth = false;
  // Means of the even- and odd-numbered samples, each pixel's count and its variance.
  bool halves = false;
  // --film-transparent: alpha is the fraction of camera samples that hit something, and a
  // camera ray that misses adds no background (the RGB is premultiplied by that alpha).
  bool coverage = false;
  bool any() const { return albedo || normal || depth || halves || coverage; }
  bool counts_hits() const { return depth || coverage; }
};

// A finished frame: linear RGB and the requested outputs, row-major, top row first.
// Where an image lies in the frame it was cut from (--crop): its top-left pixel at (x, y) of
// a full_width x full_height frame. A zero full size: the image is the whole frame.
struct FrameWindow {
  int x = 0, y = 0, full_width = 0, full_height = 0;
  bool cropped() const { return full_width > 0; }
};

struct FrameImage {
  int width = 0, height = 0;
  int samples_per_pixel = 0;  // the fewest any pixel got
  std::vector<float> rgb;  // 3 per pixel
  std::vector<float> albedo, normal;  // 3 per pixel, when requested
  // 1 per pixel, when requested: the mean camera-space depth of the samples that hit
  // something; +infinity where none did (compositors read 0 as "at the camera").
  std::vector<float> depth;
  // 1 per pixel with coverage: the fraction of its samples whose camera ray hit something,
  // the premultiplied RGB's alpha. Empty: A is 1 everywhere.
  std::vector<float> alpha;
  std::vector<float> cost;  // 1 per pixel, when requested: CPU seconds spent on the pixel's tile
  // With the halves AOV: the means of the even-numbered (s % 2 == 0) and odd-numbered
  // samples, 3 per pixel; albedo and normal ones only when those AOVs are on too.
  std::vector<float> rgb_even, rgb_odd, albedo_even, albedo_odd, normal_even, normal_odd;
  std::vector<std::uint32_t> pixel_samples;  // with halves or adaptive sampling: each pixel's count
  // With the halves AOV, 3 per pixel: the variance of the pixel's mean, per channel, estimated
  // from its samples (s^2 / n); 0 where it has fewer than 2.
  std::vector<float> rgb_variance;
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
  std::vector<std::uint32_t> samples, hits;  // hits: with depth or coverage
  // The sums of the odd-numbered samples alone, kept with the halves AOV or adaptive
  // sampling (albedo and normal ones when those AOVs are on): the even half is the total
  // minus these, so a second full set of sums is never needed.
  std::vector<glm::dvec3> radiance_odd;
  std::vector<vec3> albedo_odd, normal_odd;
  // With the halves AOV: the sums of each sample's squared radiance, per channel (each
  // pixel's variance: what the denoiser tells fireflies from highlights by).
  std::vector<glm::dvec3> radiance_sq;
  // Adaptive sampling only: 1 where the last convergence check stopped the pixel, and the
  // sample count of the wave after which that check ran (0: none yet). Both decide which
  // pixels the next wave renders, so a resumed film must carry them.
  std::vector<std::uint8_t> converged;
  std::uint32_t checked_at = 0;
  std::uint64_t dropped = 0;

  static FilmState empty(int width, int height, AovSelection aovs, bool adaptive = false);
  std::size_t pixel_count() const { return samples.size(); }
  bool keeps_odd() const { return !radiance_odd.empty(); }
  bool adaptive() const { return !converged.empty(); }
};

// Samples still to take before every pixel is done: converged, or at `spp`.
std::uint64_t samples_left(const FilmState& film, int spp);

// What one pixel's tile adds to it: sums over `samples` consecutive samples (of the radiance
// and of its square), and the sums over the odd-numbered ones among them.
struct PixelSums {
  std::uint32_t samples = 0, hits = 0;
  glm::dvec3 radiance{0.0}, radiance_odd{0.0}, radiance_sq{0.0};
  vec3 albedo{0.0f}, albedo_odd{0.0f}, normal{0.0f}, normal_odd{0.0f};
  float depth = 0.0f;
};

class Film {
 public:
  Film(int width, int height, AovSelection aovs, bool adaptive = false);
  explicit Film(FilmState state);  // continues from a checkpoint

  int width() const { return state_.width; }
  int height() const { return state_.height; }

  // Added by the only thread that owns the pixel's tile. Each pixel keeps its own sample
  // count, so a render stopped between tiles is still a complete image, every pixel the
  // mean of the samples it got.
  void add(int x, int y, const PixelSums& sums);

  std::uint32_t samples(int x, int y) const { return state_.samples[index(x, y)]; }
  bool converged(int x, int y) const { return state_.adaptive() && state_.converged[index(x, y)]; }
  std::uint32_t min_samples() const;
  std::uint64_t samples_left(int spp) const { return tessera::samples_left(state_, spp); }
  std::uint64_t converged_pixels() const;
  FrameImage resolve() const;

  void set_dropped(std::uint64_t dropped) { state_.dropped = dropped; }
  const FilmState& state() const { return state_; }
  FilmState& mutable_state() { return state_; }  // for the convergence check between waves
  FilmState take_state() { return std::move(state_); }

 private:
  std::size_t index(int x, int y) const { return static_cast<std::size_t>(y) * state_.width + x; }
  FilmState state_;
};

}  // namespace tessera
