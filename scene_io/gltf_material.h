// glTF materials and images -> the renderer's plain Material and Image.
#pragma once

#include <memory>
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

// Each image's decoded bytes, by index, moved out of the model (which keeps its shape and
// mimeType) to be shared by every scene converted from it; null where none were decoded.
using SharedPixels = std::shared_ptr<const std::vector<std::uint8_t>>;
std::vector<SharedPixels> take_image_pixels(tinygltf::Model& model);

// Every image, by index, sharing the bytes take_image_pixels took.
std::vector<Image> convert_images(const tinygltf::Model& model, const std::vector<SharedPixels>& pixels,
                                  const std::string& file);

}  // namespace tessera
