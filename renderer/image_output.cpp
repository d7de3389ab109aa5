#include "renderer/image_output.h"
#include "renderer/display_transform.h"


#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <thread>
#include <set>

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfFloatAttribute.h>
#include <OpenEXR/ImfDoubleAttribute.h>
#include <OpenEXR/ImfMatrixAttribute.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfThreading.h>

#include "renderer/exr_layers.h"
#include "renderer/file_output.h"
#include "renderer/image_codec.h"
#include "renderer/resume_layers.h"
#include "renderer/texture.h"

#ifndef TESSERA_VERSION
#define TESSERA_VERSION "unknown"
#endif

namespace tessera {

std::string tessera_version() { return TESSERA_VERSION; }

namespace fs = std::filesystem;

namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
  return ext;
}

bool is_float_format(const std::string& ext) {
  return ext == ".hdr" || ext == ".tif" || ext == ".tiff" || ext == ".pfm";
}

Imath::M44f to_imath(const glm::mat4& m) {
  // Imath multiplies row vectors (v * M): its [i][j] is glm's column i, row j.
  Imath::M44f out;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) out[i][j] = m[i][j];
  return out;
}

// One EXR channel from interleaved floats, converted to half when asked.
struct ChannelData {
  std::string name;
  std::vector<float> f;
  std::vector<Imath::half> h;
};

void add_channels(std::vector<ChannelData>& out, const std::vector<float>& src, int stride,
                  const std::vector<std::string>& names) {
  const std::size_t n = src.size() / stride;
  for (int c = 0; c < static_cast<int>(names.size()); ++c) {
    ChannelData ch{names[c], std::vector<float>(n), {}};
    for (std::size_t i = 0; i < n; ++i) ch.f[i] = src[i * stride + c];
    out.push_back(std::move(ch));
  }
}

// Every attribute of `source`'s header but its layout, which is the new file's own.
void copy_attributes(const std::string& source, Imf::Header& header) {
  static const std::set<std::string> kLayout = {"channels", "compression", "dataWindow", "displayWindow", "lineOrder",
                                                "pixelAspectRatio", "screenWindowCenter", "screenWindowWidth",
                                                "tiles", "type", "name", "version", "chunkCount",
                                                "tesseraResume", "tesseraFingerprint"};  // no resume layers here
  Imf::InputFile in(source.c_str());
  for (auto it = in.header().begin(); it != in.header().end(); ++it)
    if (!kLayout.count(it.name())) header.insert(it.name(), it.attribute());
}

std::vector<ChannelData> exr_channels(const FrameImage& img) {
  std::vector<ChannelData> channels;
  for (const ExrLayer& layer : exr_layers()) {
    const std::vector<float>& pixels = img.*layer.pixels;
    if (!pixels.empty()) add_channels(channels, pixels, static_cast<int>(layer.channels.size()), layer.channels);
  }
  channels.push_back({"A", std::vector<float>(static_cast<std::size_t>(img.width) * img.height, 1.0f), {}});
  if (!img.pixel_samples.empty())
    add_channels(channels, std::vector<float>(img.pixel_samples.begin(), img.pixel_samples.end()), 1, {kSamplesChannel});
  for (const auto& [name, values] : img.extra_channels) add_channels(channels, values, 1, {name});
  return channels;
}

void write_exr(const std::string& path, const FrameImage& img, const ImageWriteParams& params) {
  enable_exr_threads();
  std::vector<ChannelData> channels = exr_channels(img);
  const FrameMetadata& m = params.metadata;
  const Imath::Box2i data_window = exr_data_window(params.window, img.width, img.height);
  Imf::Header header(exr_display_window(params.window, img.width, img.height), data_window);
  header.compression() = Imf::ZIP_COMPRESSION;
  header.insert("samplesPerPixel", Imf::IntAttribute(img.samples_per_pixel));
  header.insert("renderTimeSeconds", Imf::DoubleAttribute(m.render_seconds));
  header.insert("seed", Imf::IntAttribute(static_cast<int>(m.seed)));
  if (!m.sampler.empty()) header.insert("sampler", Imf::StringAttribute(m.sampler));
  if (!m.pixel_filter.empty()) header.insert("pixelFilter", Imf::StringAttribute(m.pixel_filter));
  header.insert("threads", Imf::IntAttribute(m.threads));
  header.insert("tileSize", Imf::IntAttribute(m.tile_size));
  header.insert("maxBounces", Imf::IntAttribute(m.max_bounces));
  header.insert("droppedSamples", Imf::DoubleAttribute(static_cast<double>(m.dropped_samples)));
  header.insert("worldToCamera", Imf::M44fAttribute(to_imath(m.world_to_camera)));
  header.insert("worldToNDC", Imf::M44fAttribute(to_imath(m.world_to_ndc)));
  header.insert("partial", Imf::IntAttribute(m.partial ? 1 : 0));
  if (m.target_spp > 0) header.insert("targetSamplesPerPixel", Imf::IntAttribute(m.target_spp));
  if (m.noise_threshold > 0.0f) {
    header.insert("noiseThreshold", Imf::FloatAttribute(m.noise_threshold));
    header.insert("minSamplesPerPixel", Imf::IntAttribute(m.min_spp));
    header.insert("convergedPixels", Imf::DoubleAttribute(static_cast<double>(m.converged_pixels)));
  }
  if (m.denoised) header.insert("denoised", Imf::IntAttribute(1));
  header.insert("software", Imf::StringAttribute("tessera " + tessera_version()));
  header.insert("tesseraVersion", Imf::StringAttribute(tessera_version()));
  if (!m.scene_path.empty()) header.insert("scene", Imf::StringAttribute(m.scene_path));
  if (!m.camera_name.empty()) header.insert("camera", Imf::StringAttribute(m.camera_name));
  if (!m.material_variant.empty()) header.insert("materialVariant", Imf::StringAttribute(m.material_variant));
  if (m.animated) header.insert("sceneTime", Imf::FloatAttribute(m.scene_time));
  if (m.shutter_open < m.shutter_close) {  // motion blur: what the samples' times spanned
    header.insert("shutterOpen", Imf::FloatAttribute(m.shutter_open));
    header.insert("shutterClose", Imf::FloatAttribute(m.shutter_close));
  }
  if (m.frame >= 0) {
    header.insert("frame", Imf::IntAttribute(m.frame));
    header.insert("framesPerSecond", Imf::FloatAttribute(m.frames_per_second));
  }
  if (!params.header_from.empty()) copy_attributes(params.header_from, header);

  const Imf::PixelType type = params.half ? Imf::HALF : Imf::FLOAT;
  Imf::FrameBuffer fb;
  for (ChannelData& ch : channels) {
    header.channels().insert(ch.name, Imf::Channel(type));
    char* base;
    std::size_t size;
    if (params.half) {
      ch.h.assign(ch.f.begin(), ch.f.end());
      base = reinterpret_cast<char*>(ch.h.data());
      size = sizeof(Imath::half);
    } else {
      base = reinterpret_cast<char*>(ch.f.data());
      size = sizeof(float);
    }
    fb.insert(ch.name, Imf::Slice::Make(type, base, data_window, size, size * img.width));
  }
  std::optional<ResumeLayers> resume;
  if (params.resume_film) {
    resume.emplace(*params.resume_film, params.resume_settings);
    resume->insert_into(header, fb, data_window);
  }
  Imf::OutputFile file(path.c_str(), header);
  file.setFrameBuffer(fb);
  file.writePixels(img.height);
}

// Some of OpenImageIO's writers do not report a failed write (PNG leaves a truncated file
// and says nothing; JPEG's library exits the process on a full disk), so the image is encoded
// into memory and written by write_bytes_file, which checks every write and the fsync.
// A writer that went straight to the file: read it back, so a truncated file is an error.
void write_oiio_pixels(const std::string& path, int width, int height, PixelType type, const void* pixels) {
  EncodedImage encoded;
  try {
    encoded = image_codec().encode(path, width, height, type, pixels, "tessera " + tessera_version());
  } catch (const std::runtime_error& e) {
    throw OutputError(path + ": " + e.what());
  }
  if (encoded.in_memory) {
    write_bytes_file(path, encoded.bytes.data(), encoded.bytes.size());
    return;
  }
  try {
    image_codec().read(path);
  } catch (const std::runtime_error&) {
    throw OutputError(path + ": the written file does not read back (is the disk full?)");
  }
}

void write_oiio(const std::string& path, const FrameImage& img, const ImageWriteParams& params) {
  if (is_float_format(lower_extension(path))) {
    const float scale = std::exp2(params.exposure);
    std::vector<float> scaled(img.rgb);
    for (float& v : scaled) v *= scale;
    write_oiio_pixels(path, img.width, img.height, PixelType::float32, scaled.data());
  } else {
    const std::vector<std::uint8_t> rgb = to_display_rgb8(img.rgb, params.exposure, params.display);
    write_oiio_pixels(path, img.width, img.height, PixelType::uint8, rgb.data());
  }
}

}  // namespace

void enable_exr_threads() {
  static const bool once = [] {
    Imf::setGlobalThreadCount(static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
    return true;
  }();
  (void)once;
}

bool is_exr_path(const std::string& path) { return lower_extension(path) == ".exr"; }

void check_output_path(const std::string& path) {
  check_writable_path(path);  // first: "-o /dev/full" is a device, whatever its extension
  const std::string ext = lower_extension(path);
  if (ext != ".exr") {
    if (!image_codec().has_writer(path)) throw OutputPathError(path + ": unknown image format '" + ext + "' (use .exr, .png, .jpg, .ppm, .hdr, .tif, ...)");
  }
}

void write_image(const std::string& path, const FrameImage& image, const ImageWriteParams& params) {
  check_output_path(path);
  write_file_atomically(path, [&](const std::string& tmp) {
    if (is_exr_path(path)) write_exr(tmp, image, params);
    else write_oiio(tmp, image, params);
  });
}

void write_rgb8_image(const std::string& path, int width, int height, const std::vector<std::uint8_t>& rgb) {
  check_output_path(path);
  write_file_atomically(path, [&](const std::string& tmp) {
    write_oiio_pixels(tmp, width, height, PixelType::uint8, rgb.data());
  });
}

}  // namespace tessera
