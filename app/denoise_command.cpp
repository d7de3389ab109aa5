// tessera denoise: a rendered EXR with half buffers in, the denoised frame out (see
// denoiser/denoise.h and docs/usage.md).
#include <chrono>
#include <cmath>
#include <filesystem>
#include <set>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "app/commands.h"
#include "app/exit_codes.h"
#include "denoiser/denoise.h"
#include "renderer/image_input.h"
#include "renderer/image_output.h"

namespace tessera {

void add_denoise_command(CLI::App& app, DenoiseOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "denoise",
      "Denoise an EXR that tessera rendered: feature-guided regression (NFOR) on its half buffers\n"
      "(even.R/G/B, odd.R/G/B), guided by Albedo.R/G/B and N.X/Y/Z (and Z, even.Albedo.*, odd.Albedo.*,\n"
      "even.N.*, odd.N.*, spp when present).");
  cmd->add_option("input", o.input, "The rendered EXR")->required();
  cmd->add_option("-o,--output", o.output,
                  "Output EXR: R,G,B,A denoised, noisy.R/G/B the input's beauty, every other channel (not the resume layers) and "
                  "the header carried over")
      ->required();
  cmd->add_option("--preview", o.preview, "Also write the denoised frame as a display-referred image (sRGB), e.g. out.png");
  cmd->add_option("--threads", o.threads, "Threads [default: all cores]")->check(CLI::Range(1, 1024));
  cmd->add_flag("-q,--quiet", o.quiet, "No summary (errors still print)");
}

namespace {

const std::vector<std::string> kRgb = {"R", "G", "B"};

std::vector<std::string> prefixed(const std::string& prefix, const std::vector<std::string>& names) {
  std::vector<std::string> out;
  for (const std::string& n : names) out.push_back(prefix + n);
  return out;
}

// The channels denoising cannot do without; refused in one message naming them all.
void require_channels(const ExrChannels& exr, const std::string& path) {
  std::vector<std::string> missing;
  for (const auto& group : {prefixed("even.", kRgb), prefixed("odd.", kRgb), prefixed("Albedo.", kRgb),
                            prefixed("N.", {"X", "Y", "Z"})})
    for (const std::string& name : group)
      if (!exr.has(name)) missing.push_back(name);
  if (missing.empty()) return;
  throw UsageError(fmt::format("{}: cannot be denoised: missing channel{} {} (render it with the half buffers and "
                               "--aov albedo,normal)",
                               path, missing.size() > 1 ? "s" : "", fmt::join(missing, ", ")));
}

DenoiseInput denoise_input(const ExrChannels& exr) {
  DenoiseInput in;
  in.width = exr.width, in.height = exr.height;
  in.color_even = exr.interleave(prefixed("even.", kRgb));
  in.color_odd = exr.interleave(prefixed("odd.", kRgb));
  in.albedo = exr.interleave(prefixed("Albedo.", kRgb));
  in.normal = exr.interleave({"N.X", "N.Y", "N.Z"});
  // The feature halves only as a complete set (the denoiser takes all four or none).
  auto ae = exr.interleave(prefixed("even.Albedo.", kRgb)), ao = exr.interleave(prefixed("odd.Albedo.", kRgb));
  auto ne = exr.interleave({"even.N.X", "even.N.Y", "even.N.Z"}), no = exr.interleave({"odd.N.X", "odd.N.Y", "odd.N.Z"});
  if (!ae.empty() && !ao.empty() && !ne.empty() && !no.empty()) {
    in.albedo_even = std::move(ae), in.albedo_odd = std::move(ao);
    in.normal_even = std::move(ne), in.normal_odd = std::move(no);
  }
  in.depth = exr.interleave({"Z"});
  in.samples = exr.interleave({"spp"});
  return in;
}

// The input's beauty, or, in a file without one, the halves' sample-weighted mean.
std::vector<float> noisy_beauty(const ExrChannels& exr, const DenoiseInput& in) {
  std::vector<float> rgb = exr.interleave(kRgb);
  if (!rgb.empty()) return rgb;
  rgb.resize(in.color_even.size());
  for (std::size_t i = 0; i < rgb.size(); ++i) {
    const float n = in.samples.empty() ? 2.0f : in.samples[i / 3];
    const float ne = std::ceil(n / 2), no = std::floor(n / 2);
    rgb[i] = n > 0 ? (ne * in.color_even[i] + no * in.color_odd[i]) / (ne + no) : 0.0f;
  }
  return rgb;
}

FrameImage output_frame(ExrChannels exr, const DenoiseInput& in, std::vector<float> denoised) {
  FrameImage f;
  f.width = exr.width, f.height = exr.height;
  f.rgb = std::move(denoised);
  f.noisy_rgb = noisy_beauty(exr, in);
  f.albedo = in.albedo;
  f.normal = in.normal;
  f.depth = in.depth;
  // Everything else as it was, but what write_image writes itself and the resume layers
  // (a denoised frame is not resumable).
  static const std::set<std::string> kOwn = {"R", "G", "B", "A", "Albedo.R", "Albedo.G", "Albedo.B", "N.X", "N.Y",
                                             "N.Z", "Z", "noisy.R", "noisy.G", "noisy.B"};
  for (auto& [name, values] : exr.channels)
    if (!kOwn.count(name) && name.rfind("tessera.", 0) != 0) f.extra_channels.emplace_back(name, std::move(values));
  return f;
}

bool is_exr_path(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".exr";
}

}  // namespace

int run_denoise(const DenoiseOptions& o) {
  if (!is_exr_path(o.output)) throw UsageError(o.output + ": the denoised frame must be written as .exr");
  check_output_path(o.output);  // before any work
  if (!o.preview.empty()) check_output_path(o.preview);
  ExrChannels exr = read_exr_channels(o.input);
  require_channels(exr, o.input);
  const DenoiseInput in = denoise_input(exr);
  DenoiseParams params;
  params.threads = o.threads;
  const auto start = std::chrono::steady_clock::now();
  DenoiseResult result = denoise(in, params);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  ImageWriteParams write;
  write.header_from = o.input;
  const FrameImage frame = output_frame(std::move(exr), in, std::move(result.rgb));
  write_image(o.output, frame, write);
  if (!o.preview.empty()) write_image(o.preview, frame, {});
  if (!o.quiet)
    fmt::print(stderr, "tessera: denoised {} ({}x{}) in {:.2f} s; wrote {}{}\n", o.input, in.width, in.height, seconds,
               o.output, o.preview.empty() ? "" : " and " + o.preview);
  return kExitSuccess;
}

}  // namespace tessera
