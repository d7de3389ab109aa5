// glTF materials and images -> the renderer's plain Material and Image.
#pragma once

#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "renderer/scene/scene.h"

namespace tessera {

std::vector<Material> convert_materials(const tinygltf::Model& model, const std::string& file,
                                        std::vector<std::string>& warnings);
std::vector<Image> convert_images(const tinygltf::Model& model, const std::string& file);

}  // namespace tessera
