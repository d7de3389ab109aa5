// Converts one glTF mesh primitive to the renderer's TriangleMesh.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "renderer/description/scene.h"
#include "scene_io/base/gltf_accessor.h"

namespace tessera {

// nullopt for points and lines (skipped, with a warning). `what` names the primitive.
// The material index is copied as is; the caller validates it.
std::optional<TriangleMesh> convert_primitive(const AccessorReader& reader,
                                              const tinygltf::Primitive& prim,
                                              const std::string& what,
                                              std::vector<std::string>& warnings);

// Morph targets (the specification's 3.7.2.2): each target's POSITION, NORMAL and TANGENT
// displacements added to the primitive's attributes times its weight (normals and tangents
// renormalised). Throws SceneLoadError for targets whose accessors do not match the
// primitive's vertex count, or weights that do not match the number of targets.
void apply_morph_targets(const AccessorReader& reader, const tinygltf::Primitive& prim, const std::vector<float>& weights,
                         const std::string& what, TriangleMesh& mesh);

}  // namespace tessera
