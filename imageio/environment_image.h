// An environment map file decoded for the renderer's Environment (EnvironmentParams::image).
#pragma once

#include <memory>
#include <string>

#include "renderer/util/float_image.h"

namespace tessera {

// Any format OpenImageIO reads. Throws std::invalid_argument naming the file when it cannot
// be read or its size is unusable for an equirectangular map (checked from the header first).
std::shared_ptr<const FloatImage> read_environment_image(const std::string& path);

}  // namespace tessera
