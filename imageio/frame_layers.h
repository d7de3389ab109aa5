// A frame's channels grouped into layers as compositors group them, by the name before the
// last '.': "RGBA" (R, G, B, A), "Albedo" (Albedo.R/G/B), "N" (N.X/Y/Z), "Z", "even",
// "variance", "spp", and any other channel by its own prefix. The EXR writer lays a frame out
// from these layers; the Python module hands them out as arrays and takes them back.
#pragma once

#include <string>
#include <vector>

#include "imageio/image_input.h"
#include "renderer/film/film.h"

namespace tessera {

struct ImageLayer {
  std::string name;
  std::vector<std::string> channels;  // the EXR's channel names, in the layer's order
  std::vector<float> pixels;  // interleaved: channels.size() per pixel, row-major, top row first
};

// The layers tessera writes for `image` (imageio/exr_layers.h), RGBA first: A is the coverage,
// or 1 where the frame has none; then each AOV, the sample counts and the extra channels.
std::vector<ImageLayer> frame_layers(const FrameImage& image);

// The layer a channel belongs to: "RGBA" for R, G, B and A, else its name up to the last '.'
// ("even.Albedo" for even.Albedo.R), or the whole name when it has none ("Z").
std::string layer_of_channel(const std::string& channel);

// Every channel of `exr` in its layer; a layer's channels in tessera's order when tessera
// writes that layer, else R, G, B, A, then X, Y, Z, W, then by name.
std::vector<ImageLayer> channel_layers(const ExrChannels& exr);

// The EXR channel names of a layer of `count` channels named `name`: R, G, B[, A] for "RGBA"
// (or "RGB"); a layer tessera writes, its own (when the count matches); else NAME for one
// channel, NAME.X/Y for two, NAME.R/G/B[/A] for three or four. Throws std::invalid_argument
// naming the layer when no name fits.
std::vector<std::string> layer_channel_names(const std::string& name, int count);

// The channels of `layers`, each width x height, by name (the inverse of channel_layers).
ExrChannels layers_to_channels(const std::vector<ImageLayer>& layers, int width, int height);

}  // namespace tessera
