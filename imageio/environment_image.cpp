#include "imageio/environment_image.h"

#include <stdexcept>

#include "imageio/image_codec.h"

namespace tessera {

namespace {

FloatImage decode(const std::string& path) {
  try {
    return image_codec().read(path);
  } catch (const std::runtime_error& e) {
    throw std::invalid_argument(path + ": " + e.what());
  }
}

}  // namespace

std::shared_ptr<const FloatImage> read_environment_image(const std::string& path) {
  FloatImage img;
  if (!image_codec().read_size(path, img)) img = decode(path);  // names the reason
  if (img.width < 2 || img.height < 1 || img.channels < 1 || static_cast<double>(img.width) * img.height > 1 << 28)
    throw std::invalid_argument(path + ": has an unusable size for an environment map");
  return std::make_shared<const FloatImage>(decode(path));
}

}  // namespace tessera
