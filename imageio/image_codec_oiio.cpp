// The image module: tessera's ImageCodec on OpenImageIO, built as libtessera_oiio.so and
// loaded on first use (imageio/image_codec.h says why).
#include <stdexcept>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include "imageio/image_codec.h"

namespace tessera {
namespace {

class OiioCodec final : public ImageCodec {
 public:
  bool read_size(const std::string& path, FloatImage& size) const override {
    auto in = OIIO::ImageInput::open(path);
    if (!in) return false;
    size.width = in->spec().width;
    size.height = in->spec().height;
    size.channels = in->spec().nchannels;
    return true;
  }

  FloatImage read(const std::string& path) const override {
    auto in = OIIO::ImageInput::open(path);
    if (!in) throw std::runtime_error("cannot be read as an image (" + OIIO::geterror() + ")");
    const OIIO::ImageSpec& spec = in->spec();
    FloatImage out{spec.width, spec.height, spec.nchannels, {}};
    if (spec.width < 1 || spec.height < 1 || spec.nchannels < 1 || double(spec.width) * spec.height * spec.nchannels > 1 << 30)
      throw std::runtime_error("has an unusable size");
    out.pixels.resize(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, out.pixels.data()))
      throw std::runtime_error("could not be decoded (" + in->geterror() + ")");
    return out;
  }

  bool has_writer(const std::string& path) const override { return OIIO::ImageOutput::create(path) != nullptr; }

  EncodedImage encode(const std::string& path, int width, int height, PixelType type, const void* pixels,
                      const std::string& software) const override {
    const OIIO::TypeDesc td = type == PixelType::uint8 ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT;
    auto out = OIIO::ImageOutput::create(path);
    if (!out) throw std::runtime_error("no image writer for this format (" + OIIO::geterror() + ")");
    OIIO::ImageSpec spec(width, height, 3, td);
    spec.attribute("Software", software);
    EncodedImage encoded;
    OIIO::Filesystem::IOVecOutput memory(encoded.bytes);
    encoded.in_memory = out->supports("ioproxy") && out->set_ioproxy(&memory);
    if (!out->open(path, spec) || !out->write_image(td, pixels) || !out->close()) throw std::runtime_error(out->geterror());
    return encoded;
  }

  std::vector<float> color_map_srgb(const std::string& name, const std::vector<float>& t) const override {
    const int n = static_cast<int>(t.size());
    if (n == 0) return {};
    OIIO::ImageBuf values(OIIO::ImageSpec(n, 1, 1, OIIO::TypeDesc::FLOAT));
    for (int i = 0; i < n; ++i) values.setpixel(i, 0, &t[i], 1);
    // OpenImageIO's maps are linear light, like its images.
    const OIIO::ImageBuf linear = OIIO::ImageBufAlgo::color_map(values, 0, name);
    const OIIO::ImageBuf srgb = OIIO::ImageBufAlgo::colorconvert(linear, "linear", "sRGB");
    std::vector<float> out(3 * n);
    for (int i = 0; i < n; ++i) srgb.getpixel(i, 0, &out[3 * i], 3);
    return out;
  }
};

}  // namespace
}  // namespace tessera

extern "C" __attribute__((visibility("default"))) const tessera::ImageCodec* tessera_image_codec() {
  static const tessera::OiioCodec codec;
  return &codec;
}
