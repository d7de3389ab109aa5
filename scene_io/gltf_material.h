// glTF materials and images -> the renderer's plain Material and Image.
#pragma once

#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "renderer/scene/scene.h"
#include "scene_io/gltf_defects.h"

namespace tessera {

std::vector<Material> convert_materials(const tinygltf::Model& model, const std::string& file,
                                        const GltfDefects& defects, std::vector<std::string>& warnings);
std::vector<Image> convert_images(const tinygltf::Model& model, const std::string& file);

}  // namespace tessera
