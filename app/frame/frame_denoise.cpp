#include "app/frame/frame_denoise.h"

#include <chrono>

#include "imageio/exr_layers.h"
#include "renderer/sampling/sampler.h"

namespace tessera {

const std::vector<std::string>& denoise_channels() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const ExrLayer& layer : exr_layers()) {
      const auto p = layer.pixels;
      if (p == &FrameImage::rgb || p == &FrameImage::rgb_even || p == &FrameImage::rgb_odd ||
          p == &FrameImage::albedo || p == &FrameImage::normal)
        out.insert(out.end(), layer.channels.begin(), layer.channels.end());
    }
    return out;
  }();
  return names;
}

DenoiseParams denoise_params(int threads, const std::string& sampler) {
  DenoiseParams p;
  p.threads = threads;
  if (sampler == sampler_name(SamplerKind::independent)) p.half_variance_bias = 1.0f;
  return p;
}

DenoiseInput denoise_input(const FrameImage& frame) {
  DenoiseInput in;
  in.width = frame.width, in.height = frame.height;
  in.color_even = frame.rgb_even, in.color_odd = frame.rgb_odd;
  in.albedo = frame.albedo, in.normal = frame.normal;
  // The feature halves only as a complete set: the denoiser takes all four or none.
  if (!frame.albedo_even.empty() && !frame.albedo_odd.empty() && !frame.normal_even.empty() &&
      !frame.normal_odd.empty()) {
    in.albedo_even = frame.albedo_even, in.albedo_odd = frame.albedo_odd;
    in.normal_even = frame.normal_even, in.normal_odd = frame.normal_odd;
  }
  in.depth = frame.depth;
  in.samples.assign(frame.pixel_samples.begin(), frame.pixel_samples.end());
  in.variance = frame.rgb_variance;
  return in;
}

double denoise_frame(FrameImage& frame, const DenoiseParams& params) {
  const auto start = std::chrono::steady_clock::now();
  DenoiseResult result = denoise(denoise_input(frame), params);
  frame.noisy_rgb = std::move(frame.rgb);
  frame.rgb = std::move(result.rgb);
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace tessera
