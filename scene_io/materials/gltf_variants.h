// KHR_materials_variants: the file's named material variants (the root's
// extensions.KHR_materials_variants.variants) and, per mesh primitive, the material each
// variant gives it (the primitive's extensions.KHR_materials_variants.mappings).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <tiny_gltf.h>

namespace tessera {

inline constexpr const char* kMaterialsVariants = "KHR_materials_variants";

// The variants' names, by index; empty when the file does not use the extension.
// Throws SceneLoadError(file, ...) when the root's extension object is malformed.
std::vector<std::string> read_material_variants(const tinygltf::Model& model, const std::string& file);

// The index of the variant `wanted` names: a variant's name first, else its index. Throws
// SceneLoadError(file, ...) listing the file's variants when there is no such variant.
int choose_material_variant(const std::vector<std::string>& names, const std::string& wanted,
                            const std::string& file);

// The material `prim` has with variant `variant` active (-1: none): its mapping's material
// when one lists the variant, else prim.material. Every mapping is checked whatever the
// variant: a material or variant index out of range, a variant mapped twice, or a mapping
// that is not {material, variants} throws SceneLoadError(file, ...) naming `what` (the
// primitive, "mesh 0 primitive 1").
int material_for_variant(const tinygltf::Primitive& prim, int variant, std::size_t variant_count,
                         std::size_t material_count, const std::string& file, const std::string& what);

// Every material index a mapping of `prim` gives, unchecked (what is not an index is left out).
std::vector<int> mapped_materials(const tinygltf::Primitive& prim);

}  // namespace tessera
