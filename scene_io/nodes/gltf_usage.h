// What the chosen scene uses, for the policy in docs/reliability.md: an error in a used object
// refuses the file, the same error in an unused one is a warning. Used are the nodes reachable
// from the scene's roots; the meshes, cameras and lights they place; the materials of those meshes' primitives,
// each KHR_materials_variants mapping's included (any variant can be chosen); the skins of the
// nodes that place a mesh; and the animations that play and move something the scene shows (a
// channel on a node, or an ancestor of one, that places a mesh, camera or light, or on a joint
// of a used skin or its ancestors). Textures, images and samplers are used through the used
// materials (conversion reads them from there).
#pragma once

#include <vector>

#include <tiny_gltf.h>

namespace tessera {

struct GltfUsage {
  std::vector<bool> nodes, meshes, cameras, lights, materials, skins, animations;  // by index in the file
};

// `roots` are the scene's root nodes, `parent` every node's parent (-1: none; the hierarchy
// already checked), `playing` the animations chosen to play. Indices out of range are ignored:
// conversion refuses them where it reads them.
GltfUsage find_used_objects(const tinygltf::Model& model, const std::vector<int>& roots,
                            const std::vector<int>& parent, const std::vector<int>& playing);

}  // namespace tessera
