// The node hierarchy of a glTF file, checked before it is walked: glTF nodes form disjoint
// strict trees, so a node has at most one parent, is never its own ancestor, and a scene
// lists only parentless nodes, each once. A file that breaks this could otherwise make
// the traversal loop forever or place one subtree exponentially many times.
#pragma once

#include <string>
#include <vector>

#include <tiny_gltf.h>

namespace tessera {

// The parent of every node (-1 for none). Throws SceneLoadError for a child index out of
// range, a node that is its own child or ancestor, or a node with two parents.
std::vector<int> check_node_hierarchy(const tinygltf::Model& model, const std::string& file);

// The root nodes of scene `scene`, or of every parentless node when scene is -1. Throws
// SceneLoadError for a root out of range, a root that has a parent, or a root listed twice.
std::vector<int> scene_roots(const tinygltf::Model& model, int scene, const std::vector<int>& parent,
                             const std::string& file);

}  // namespace tessera
