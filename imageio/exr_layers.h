// The EXR channels of each float layer of a FrameImage, in one table that the writer
// (image_output) and the reader (image_input) share: a frame read back has the layers it was
// written with, under the names compositors and `tessera denoise` look for.
#pragma once

#include <string>
#include <vector>

#include <ImathBox.h>

#include "renderer/film/film.h"

namespace tessera {

struct ExrLayer {
  std::vector<float> FrameImage::*pixels;  // interleaved: channels.size() floats per pixel
  std::vector<std::string> channels;
};

inline const std::vector<ExrLayer>& exr_layers() {
  static const std::vector<ExrLayer> layers = {
      {&FrameImage::rgb, {"R", "G", "B"}},
      {&FrameImage::albedo, {"Albedo.R", "Albedo.G", "Albedo.B"}},
      {&FrameImage::normal, {"N.X", "N.Y", "N.Z"}},
      {&FrameImage::depth, {"Z"}},
      {&FrameImage::cost, {"cost.time"}},
      {&FrameImage::noisy_rgb, {"noisy.R", "noisy.G", "noisy.B"}},
      {&FrameImage::rgb_even, {"even.R", "even.G", "even.B"}},
      {&FrameImage::rgb_odd, {"odd.R", "odd.G", "odd.B"}},
      {&FrameImage::albedo_even, {"even.Albedo.R", "even.Albedo.G", "even.Albedo.B"}},
      {&FrameImage::albedo_odd, {"odd.Albedo.R", "odd.Albedo.G", "odd.Albedo.B"}},
      {&FrameImage::normal_even, {"even.N.X", "even.N.Y", "even.N.Z"}},
      {&FrameImage::normal_odd, {"odd.N.X", "odd.N.Y", "odd.N.Z"}},
      {&FrameImage::rgb_variance, {"variance.R", "variance.G", "variance.B"}},
  };
  return layers;
}

// Each pixel's sample count (FrameImage::pixel_samples), as FLOAT: exact up to 2^24.
inline const char* const kSamplesChannel = "spp";

// The pixels an image of width x height covers in its frame (the EXR data window), and the
// frame (the display window): the same unless the image was cropped.
inline Imath::Box2i exr_data_window(const FrameWindow& w, int width, int height) {
  return {Imath::V2i(w.x, w.y), Imath::V2i(w.x + width - 1, w.y + height - 1)};
}
inline Imath::Box2i exr_display_window(const FrameWindow& w, int width, int height) {
  return w.cropped() ? Imath::Box2i(Imath::V2i(0, 0), Imath::V2i(w.full_width - 1, w.full_height - 1))
                     : exr_data_window(w, width, height);
}

}  // namespace tessera
