#include "imageio/frame_layers.h"

#include <algorithm>
#include <map>
#include <stdexcept>

#include <fmt/format.h>

#include "imageio/exr_layers.h"

namespace tessera {

namespace {

std::string channel_suffix(const std::string& channel) {
  const std::size_t dot = channel.rfind('.');
  return dot == std::string::npos ? channel : channel.substr(dot + 1);
}

// Colour channels first, then vector components, then the rest by name.
int channel_rank(const std::string& channel) {
  static const std::vector<std::string> kOrder = {"R", "G", "B", "A", "X", "Y", "Z", "W"};
  const auto it = std::find(kOrder.begin(), kOrder.end(), channel_suffix(channel));
  return static_cast<int>(it - kOrder.begin());
}

// The layers tessera writes, in the order it writes them.
std::vector<std::string> tessera_layer_order() {
  std::vector<std::string> order;
  for (const ExrLayer& layer : exr_layers()) order.push_back(layer_of_channel(layer.channels[0]));
  order.push_back(kSamplesChannel);
  return order;
}

}  // namespace

std::string layer_of_channel(const std::string& channel) {
  if (channel == "R" || channel == "G" || channel == "B" || channel == "A") return "RGBA";
  const std::size_t dot = channel.rfind('.');
  return dot == std::string::npos ? channel : channel.substr(0, dot);
}

std::vector<ImageLayer> frame_layers(const FrameImage& image) {
  const std::size_t n = static_cast<std::size_t>(image.width) * image.height;
  std::vector<ImageLayer> layers;
  ImageLayer rgba{"RGBA", {"R", "G", "B", "A"}, std::vector<float>(n * 4)};
  for (std::size_t i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) rgba.pixels[4 * i + c] = image.rgb[3 * i + c];
    rgba.pixels[4 * i + 3] = image.alpha.empty() ? 1.0f : image.alpha[i];
  }
  layers.push_back(std::move(rgba));
  for (const ExrLayer& layer : exr_layers()) {
    const std::vector<float>& pixels = image.*layer.pixels;
    if (layer.pixels != &FrameImage::rgb && !pixels.empty())
      layers.push_back({layer_of_channel(layer.channels[0]), layer.channels, pixels});
  }
  if (!image.pixel_samples.empty())
    layers.push_back({kSamplesChannel, {kSamplesChannel}, std::vector<float>(image.pixel_samples.begin(), image.pixel_samples.end())});
  // Extra channels (a denoised frame's carried-over halves) grouped by their layers.
  ExrChannels extra;
  extra.width = image.width, extra.height = image.height;
  for (const auto& [name, values] : image.extra_channels) extra.channels[name] = values;
  for (ImageLayer& layer : channel_layers(extra)) layers.push_back(std::move(layer));
  return layers;
}

std::vector<ImageLayer> channel_layers(const ExrChannels& exr) {
  std::map<std::string, std::vector<std::string>> by_layer;
  for (const auto& entry : exr.channels)
    if (entry.first.rfind("tessera.", 0) != 0) by_layer[layer_of_channel(entry.first)].push_back(entry.first);
  std::vector<std::string> order;
  for (const std::string& name : tessera_layer_order())
    if (by_layer.count(name) && std::find(order.begin(), order.end(), name) == order.end()) order.push_back(name);
  for (const auto& entry : by_layer)
    if (std::find(order.begin(), order.end(), entry.first) == order.end()) order.push_back(entry.first);
  std::vector<ImageLayer> layers;
  for (const std::string& name : order) {
    std::vector<std::string> channels = by_layer[name];
    std::sort(channels.begin(), channels.end(), [](const std::string& a, const std::string& b) {
      return std::make_pair(channel_rank(a), a) < std::make_pair(channel_rank(b), b);
    });
    layers.push_back({name, channels, exr.interleave(channels)});
  }
  return layers;
}

std::vector<std::string> layer_channel_names(const std::string& name, int count) {
  static const std::vector<std::string> kColour = {"R", "G", "B", "A"}, kVector = {"X", "Y"};
  const bool colour = name == "RGBA" || name == "RGB";
  if (colour && (count == 3 || count == 4)) return {kColour.begin(), kColour.begin() + count};
  for (const ExrLayer& layer : exr_layers())
    if (!colour && layer_of_channel(layer.channels[0]) == name && static_cast<int>(layer.channels.size()) == count)
      return layer.channels;
  std::vector<std::string> names;
  if (!colour && count == 1) names = {name};
  if (!colour && count == 2)
    for (const std::string& c : kVector) names.push_back(name + "." + c);
  if (!colour && (count == 3 || count == 4))
    for (int c = 0; c < count; ++c) names.push_back(name + "." + kColour[c]);
  if (names.empty())
    throw std::invalid_argument(fmt::format("layer '{}' has {} channels: {}", name, count,
                                            colour ? "RGB and RGBA have 3 or 4" : "a layer has 1 to 4"));
  return names;
}

ExrChannels layers_to_channels(const std::vector<ImageLayer>& layers, int width, int height) {
  ExrChannels exr;
  exr.width = width, exr.height = height;
  const std::size_t n = static_cast<std::size_t>(width) * height;
  for (const ImageLayer& layer : layers) {
    const std::size_t stride = layer.channels.size();
    if (stride == 0 || layer.pixels.size() != n * stride)
      throw std::invalid_argument(fmt::format("layer '{}': {} values for {} channels of {}x{} pixels", layer.name,
                                              layer.pixels.size(), stride, width, height));
    for (std::size_t c = 0; c < stride; ++c) {
      std::vector<float>& values = exr.channels[layer.channels[c]];
      if (!values.empty())
        throw std::invalid_argument(fmt::format("channel {} is given twice (layer '{}')", layer.channels[c], layer.name));
      values.resize(n);
      for (std::size_t i = 0; i < n; ++i) values[i] = layer.pixels[i * stride + c];
    }
  }
  return exr;
}

}  // namespace tessera
