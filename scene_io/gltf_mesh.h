// Converts one glTF mesh primitive to the renderer's TriangleMesh.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "renderer/scene/scene.h"
#include "scene_io/gltf_accessor.h"

namespace tessera {

// nullopt for points and lines (skipped, with a warning). `what` names the primitive.
// The material index is copied as is; the caller validates it.
std::optional<TriangleMesh> convert_primitive(const AccessorReader& reader,
                                              const tinygltf::Primitive& prim,
                                              const std::string& what,
                                              std::vector<std::string>& warnings);

}  // namespace tessera
