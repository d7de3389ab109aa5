// glTF materials and images -> the renderer's plain Material and Image.
#pragma once

#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "renderer/scene/scene.h"
#include "scene_io/gltf_defects.h"

namespace tessera {

// Every material, by index. A material the scene does not use (`used`, by index) that cannot
// be converted is a warning and a default material (GltfDefects::read_object).
std::vector<Material> convert_materials(const tinygltf::Model& model, const std::string& file,
                                        const GltfDefects& defects, const std::vector<bool>& used,
                                        std::vector<std::string>& warnings);
// The sampler texture `index` uses (nullptr: the default one). Throws SceneLoadError for a
// sampler out of range or with a defect.
const tinygltf::Sampler* texture_sampler(const tinygltf::Model& model, const std::string& file, int index,
                                         const GltfDefects& defects);

std::vector<Image> convert_images(const tinygltf::Model& model, const std::string& file);

}  // namespace tessera
