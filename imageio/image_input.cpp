#include "imageio/image_input.h"

#include <algorithm>
#include <set>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfStringAttribute.h>

#include "imageio/exr_header.h"
#include "imageio/exr_layers.h"
#include "imageio/image_output.h"

namespace tessera {

std::vector<float> ExrChannels::interleave(const std::vector<std::string>& names) const {
  const std::size_t n = static_cast<std::size_t>(width) * height, stride = names.size();
  std::vector<float> out(n * stride);
  for (std::size_t c = 0; c < stride; ++c) {
    const auto it = channels.find(names[c]);
    if (it == channels.end()) return {};
    for (std::size_t i = 0; i < n; ++i) out[i * stride + c] = it->second[i];
  }
  return out;
}

ExrChannels read_exr_channels(const std::string& path) {
  enable_exr_threads();
  try {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i window = file.header().dataWindow();
    ExrChannels out;
    out.width = window.max.x - window.min.x + 1;
    out.height = window.max.y - window.min.y + 1;
    const Imath::Box2i display = file.header().displayWindow();
    if (display != window && display.min == Imath::V2i(0, 0))
      out.window = {window.min.x, window.min.y, display.max.x + 1, display.max.y + 1};
    if (const auto* s = file.header().findTypedAttribute<Imf::StringAttribute>("sampler")) out.sampler = s->value();
    out.attributes = header_attributes(file.header());
    const std::size_t n = static_cast<std::size_t>(out.width) * out.height;
    Imf::FrameBuffer fb;
    for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it) {
      if (it.channel().xSampling != 1 || it.channel().ySampling != 1) continue;  // subsampled: not ours
      std::vector<float>& data = out.channels[it.name()];
      data.resize(n);
      // The slice's origin is shifted so that the data window's first pixel lands at index 0.
      char* base = reinterpret_cast<char*>(data.data()) -
                   (static_cast<std::ptrdiff_t>(window.min.y) * out.width + window.min.x) * sizeof(float);
      fb.insert(it.name(), Imf::Slice(Imf::FLOAT, base, sizeof(float), sizeof(float) * out.width));
    }
    file.setFrameBuffer(fb);
    file.readPixels(window.min.y, window.max.y);
    return out;
  } catch (const std::exception& e) {
    throw ImageInputError(path + ": cannot be read as an OpenEXR image: " + e.what());
  }
}

FrameImage read_frame_exr(const std::string& path) { return frame_from_exr(read_exr_channels(path)); }

FrameImage frame_from_exr(ExrChannels exr) {
  FrameImage frame;
  frame.width = exr.width, frame.height = exr.height;
  std::set<std::string> used = {"A"};
  // Coverage (--film-transparent) travels with the frame; an A of 1 everywhere is no coverage.
  if (exr.has("A") && std::any_of(exr.channels["A"].begin(), exr.channels["A"].end(), [](float a) { return a != 1.0f; }))
    frame.alpha = exr.channels["A"];
  for (const ExrLayer& layer : exr_layers()) {
    frame.*layer.pixels = exr.interleave(layer.channels);
    if (!(frame.*layer.pixels).empty()) used.insert(layer.channels.begin(), layer.channels.end());
  }
  if (exr.has(kSamplesChannel)) {
    for (float n : exr.channels[kSamplesChannel]) frame.pixel_samples.push_back(static_cast<std::uint32_t>(n));
    frame.samples_per_pixel = static_cast<int>(*std::min_element(frame.pixel_samples.begin(), frame.pixel_samples.end()));
    used.insert(kSamplesChannel);
  }
  for (auto& [name, values] : exr.channels)
    if (!used.count(name) && name.rfind("tessera.", 0) != 0) frame.extra_channels.emplace_back(name, std::move(values));
  return frame;
}

}  // namespace tessera
