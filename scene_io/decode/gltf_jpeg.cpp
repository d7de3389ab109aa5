#include "scene_io/decode/gltf_jpeg.h"

#include <cstdint>
#include <cstring>
#include <memory>

#include <fmt/format.h>
#include <turbojpeg.h>

namespace tessera {
namespace {

// 2^28 pixels (1 GiB of RGBA, 16384^2): a header may claim up to 65535^2 from a few bytes.
constexpr std::uint64_t kMostPixels = std::uint64_t{1} << 28;

std::string corrupt(tjhandle tj) { return fmt::format("its JPEG data is corrupt ({})", tjGetErrorStr2(tj)); }

// Stray bytes between two segments (some cameras' and editors' JPEGs: libjpeg's "Corrupt JPEG
// data: N extraneous bytes before marker 0xXX") are skipped, every pixel decoded: stb_image,
// browsers and OpenImageIO show such images, and so does tessera.
bool only_stray_bytes(tjhandle tj) {
  return tjGetErrorCode(tj) == TJERR_WARNING &&
         std::strstr(tjGetErrorStr2(tj), "extraneous bytes before marker") != nullptr;
}

// c * k / 255 rounded, as stb_image converted CMYK: Adobe's inverted CMYK (and YCCK, which
// libjpeg turns into the same) gives each of R, G, B as its inverted ink times the black.
std::uint8_t ink_times_black(unsigned c, unsigned k) {
  const unsigned t = c * k + 128;
  return static_cast<std::uint8_t>((t + (t >> 8)) >> 8);
}

void cmyk_to_rgba(std::vector<unsigned char>& pixels) {
  for (std::size_t i = 0; i < pixels.size(); i += 4) {
    const unsigned k = pixels[i + 3];
    for (int c = 0; c < 3; ++c) pixels[i + c] = ink_times_black(pixels[i + c], k);
    pixels[i + 3] = 255;
  }
}

}  // namespace

bool is_jpeg(const unsigned char* b, int size) { return size >= 3 && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF; }

std::string decode_jpeg(tinygltf::Image* image, const unsigned char* bytes, int size) {
  const std::unique_ptr<void, int (*)(tjhandle)> tj(tjInitDecompress(), &tjDestroy);
  if (!tj) return fmt::format("libjpeg-turbo could not start ({})", tjGetErrorStr2(nullptr));
  const unsigned long length = static_cast<unsigned long>(size);
  int w = 0, h = 0, subsampling = 0, colorspace = 0;
  if (tjDecompressHeader3(tj.get(), bytes, length, &w, &h, &subsampling, &colorspace) != 0 && !only_stray_bytes(tj.get()))
    return corrupt(tj.get());
  if (static_cast<std::uint64_t>(w) * static_cast<std::uint64_t>(h) > kMostPixels)
    return fmt::format("its JPEG header gives {}x{} pixels, more than the {} tessera decodes", w, h, kMostPixels);
  const bool cmyk = colorspace == TJCS_CMYK || colorspace == TJCS_YCCK;
  image->image.resize(static_cast<std::size_t>(w) * h * 4);
  // A warning that data was patched over (a truncated file, a broken segment) is an error;
  // LIMITSCANS refuses a progressive JPEG of over 500 scans, libjpeg-turbo's guard against
  // such files' unbounded decoding time.
  if (tjDecompress2(tj.get(), bytes, length, image->image.data(), w, 0, h, cmyk ? TJPF_CMYK : TJPF_RGBA,
                    TJFLAG_LIMITSCANS) != 0 &&
      !only_stray_bytes(tj.get())) {
    std::vector<unsigned char>().swap(image->image);
    return corrupt(tj.get());
  }
  if (cmyk) cmyk_to_rgba(image->image);
  image->width = w;
  image->height = h;
  image->component = 4;
  image->bits = 8;
  image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
  return "";
}

}  // namespace tessera
