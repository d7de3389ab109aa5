// What tessera asks of OpenImageIO: decode an image file to float pixels, encode 8-bit or
// float RGB in a format named by the path's extension, and a colour map. OpenImageIO lives in
// a module (libtessera_oiio.so, imageio/image_codec_oiio.cpp) that is loaded the first time
// one of these is called: linked into the program, its ~260 shared libraries took 0.5-0.8 s
// of dynamic linking at every start, also for `--version` and for renders that write only EXR
// (which OpenEXR writes directly).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "renderer/util/float_image.h"

namespace tessera {

enum class PixelType { uint8, float32 };

struct EncodedImage {
  bool in_memory = false;  // false: the writer wrote the file itself (it has no memory output)
  std::vector<unsigned char> bytes;
};

// The interface the module implements. Errors are std::runtime_error with OpenImageIO's words
// (the caller adds the path and its own sentence).
class ImageCodec {
 public:
  virtual ~ImageCodec() = default;
  // Width, height and channels from the header alone; false when it cannot be opened.
  virtual bool read_size(const std::string& path, FloatImage& size) const = 0;
  virtual FloatImage read(const std::string& path) const = 0;
  virtual bool has_writer(const std::string& path) const = 0;
  // 3 channels per pixel; the format from the path's extension.
  virtual EncodedImage encode(const std::string& path, int width, int height, PixelType type, const void* pixels,
                              const std::string& software) const = 0;
  // OpenImageIO's named colour map (e.g. "viridis") at t in [0, 1], as sRGB triples.
  virtual std::vector<float> color_map_srgb(const std::string& name, const std::vector<float>& t) const = 0;
};

// The module, loaded on first use and kept for the process. Throws std::runtime_error naming
// the module and dlopen's reason when it cannot be loaded.
const ImageCodec& image_codec();

// The module's entry point (extern "C" so dlsym finds it by this name).
using ImageCodecEntry = const ImageCodec* (*)();
inline constexpr const char* kImageCodecEntry = "tessera_image_codec";
inline constexpr const char* kImageCodecModule = "libtessera_oiio.so";

}  // namespace tessera
