// glTF materials and images -> the renderer's plain Material and Image.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "renderer/description/scene.h"
#include "scene_io/base/gltf_defects.h"
#include "scene_io/decode/gltf_image_store.h"

namespace tessera {

// Every material, by index. A material the scene does not use (`used`, by index) that cannot
// be converted is a warning and a default material (GltfDefects::read_object).
std::vector<Material> convert_materials(const tinygltf::Model& model, const std::string& file,
                                        const GltfDefects& defects, const GltfImageStore& images,
                                        const std::vector<bool>& used, std::vector<std::string>& warnings);
// The sampler texture `index` uses (nullptr: the default one). Throws SceneLoadError for a
// sampler out of range or with a defect.
const tinygltf::Sampler* texture_sampler(const tinygltf::Model& model, const std::string& file, int index,
                                         const GltfDefects& defects);

// The images the used materials (`used`, by index) show, in increasing order.
std::vector<int> images_shown(const std::vector<Material>& materials, const std::vector<bool>& used);

// Every image, by index: those `shown` decoded (now, if not before: `images` keeps them for
// the next scene converted from the document), the rest named only, without pixels. Throws
// SceneLoadError for a shown image that cannot be decoded.
std::vector<Image> convert_images(const tinygltf::Model& model, const GltfImageStore& images,
                                  const std::vector<int>& shown, const std::string& file);

}  // namespace tessera
