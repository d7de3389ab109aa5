#include "imageio/image_output.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <thread>
#include <set>

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfMultiPartOutputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfOutputPart.h>
#include <OpenEXR/ImfPartType.h>
#include <OpenEXR/ImfThreading.h>

#include "imageio/exr_header.h"
#include "imageio/exr_layers.h"
#include "imageio/file_output.h"
#include "imageio/frame_layers.h"
#include "imageio/image_codec.h"
#include "imageio/resume_layers.h"

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
  Imf::InputFile in(source.c_str());
  for (auto it = in.header().begin(); it != in.header().end(); ++it) {
    const std::string name = it.name();
    if (!is_layout_attribute(name) && name != "tesseraResume" && name != "tesseraFingerprint")  // no resume layers here
      header.insert(name, it.attribute());
  }
}

std::vector<ChannelData> exr_channels(const FrameImage& img) {
  std::vector<ChannelData> channels;
  for (const ImageLayer& layer : frame_layers(img))
    add_channels(channels, layer.pixels, static_cast<int>(layer.channels.size()), layer.channels);
  return channels;
}

// A colour channel (R, G, B, A, or a layer's) may be stored as half with --half; depth,
// normals, counts, times and variances keep 32-bit floats, which half would round (Z to 3
// digits) or overflow (a firefly's variance beyond 65504).
bool is_colour_channel(const std::string& name) {
  if (name.rfind("variance.", 0) == 0) return false;
  const std::string last = name.substr(name.rfind('.') + 1);
  return last == "R" || last == "G" || last == "B" || last == "A";
}

void insert_channels(std::vector<ChannelData>& channels, bool half, const Imath::Box2i& data_window, int width,
                     Imf::Header& header, Imf::FrameBuffer& fb) {
  for (ChannelData& ch : channels) {
    const Imf::PixelType type = half && is_colour_channel(ch.name) ? Imf::HALF : Imf::FLOAT;
    header.channels().insert(ch.name, Imf::Channel(type));
    char* base = reinterpret_cast<char*>(ch.f.data());
    std::size_t size = sizeof(float);
    if (type == Imf::HALF) {
      ch.h.assign(ch.f.begin(), ch.f.end());
      base = reinterpret_cast<char*>(ch.h.data());
      size = sizeof(Imath::half);
    }
    fb.insert(ch.name, Imf::Slice::Make(type, base, data_window, size, size * width));
  }
}

// A resumable frame is a two-part file: the frame as compositors read it, then the film's
// exact sums in a part of their own, which layer lists built from the first part never show.
void write_resumable_exr(const std::string& path, Imf::Header& header, const Imf::FrameBuffer& fb, int height,
                         const ImageWriteParams& params) {
  const Imath::Box2i data_window = header.dataWindow();
  Imf::Header resume_header = header;  // the same windows and shared attributes, no channels
  resume_header.channels() = Imf::ChannelList();
  header.setName("rgba");
  header.setType(Imf::SCANLINEIMAGE);
  resume_header.setName(kResumePartName);
  resume_header.setType(Imf::SCANLINEIMAGE);
  Imf::FrameBuffer resume_fb;
  ResumeLayers resume(*params.resume_film, params.resume_settings, params.resume_options);
  resume.insert_into(resume_header, resume_fb, data_window);
  Imf::MultiPartOutputFile file(path.c_str(), std::vector<Imf::Header>{header, resume_header}.data(), 2);
  Imf::OutputPart frame(file, 0), film(file, 1);
  frame.setFrameBuffer(fb);
  frame.writePixels(height);
  film.setFrameBuffer(resume_fb);
  film.writePixels(height);
}

void write_exr(const std::string& path, const FrameImage& img, const ImageWriteParams& params) {
  enable_exr_threads();
  std::vector<ChannelData> channels = exr_channels(img);
  const Imath::Box2i data_window = exr_data_window(params.window, img.width, img.height);
  Imf::Header header(exr_display_window(params.window, img.width, img.height), data_window);
  header.compression() = Imf::ZIP_COMPRESSION;
  if (params.render_metadata) insert_frame_metadata(header, params.metadata, img.samples_per_pixel);
  else insert_provenance(header, params.metadata);
  if (!params.header_from.empty()) copy_attributes(params.header_from, header);
  insert_attributes(header, params.attributes);
  Imf::FrameBuffer fb;
  insert_channels(channels, params.half, data_window, img.width, header, fb);
  if (params.resume_film) return write_resumable_exr(path, header, fb, img.height, params);
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

bool is_display_format_path(const std::string& path) {
  return !is_exr_path(path) && !is_float_format(lower_extension(path));
}

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
