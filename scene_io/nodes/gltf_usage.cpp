#include "scene_io/nodes/gltf_usage.h"

#include "scene_io/materials/gltf_variants.h"

namespace tessera {
namespace {

bool in_range(int index, std::size_t size) { return index >= 0 && static_cast<std::size_t>(index) < size; }

// Marks `node` and its ancestors.
void mark_with_ancestors(int node, const std::vector<int>& parent, std::vector<bool>& marked) {
  for (int n = node; n >= 0 && !marked[n]; n = parent[n]) marked[n] = true;
}

}  // namespace

GltfUsage find_used_objects(const tinygltf::Model& model, const std::vector<int>& roots,
                            const std::vector<int>& parent, const std::vector<int>& playing) {
  const std::size_t nodes = model.nodes.size();
  GltfUsage used{std::vector<bool>(nodes, false), std::vector<bool>(model.meshes.size(), false),
                 std::vector<bool>(model.cameras.size(), false), std::vector<bool>(model.lights.size(), false),
                 std::vector<bool>(model.materials.size(), false),
                 std::vector<bool>(model.skins.size(), false), std::vector<bool>(model.animations.size(), false)};
  std::vector<bool> moves_shown(nodes, false);  // animating it moves something the scene shows
  std::vector<int> stack(roots.begin(), roots.end());
  while (!stack.empty()) {  // the hierarchy is a forest (checked), so each node comes once
    const int n = stack.back();
    stack.pop_back();
    if (!in_range(n, nodes) || used.nodes[n]) continue;
    used.nodes[n] = true;
    const tinygltf::Node& node = model.nodes[n];
    for (int c : node.children) stack.push_back(c);
    const auto light = node.extensions.find("KHR_lights_punctual");
    if (light != node.extensions.end()) {
      const int l = light->second.Has("light") ? light->second.Get("light").GetNumberAsInt() : -1;
      if (in_range(l, model.lights.size())) used.lights[l] = true;
    }
    if (node.mesh >= 0 || node.camera >= 0 || light != node.extensions.end()) mark_with_ancestors(n, parent, moves_shown);
    if (in_range(node.camera, model.cameras.size())) used.cameras[node.camera] = true;
    if (!in_range(node.mesh, model.meshes.size())) continue;
    used.meshes[node.mesh] = true;
    for (const tinygltf::Primitive& prim : model.meshes[node.mesh].primitives) {
      if (in_range(prim.material, model.materials.size())) used.materials[prim.material] = true;
      for (int m : mapped_materials(prim))
        if (in_range(m, model.materials.size())) used.materials[m] = true;
    }
    if (!in_range(node.skin, model.skins.size())) continue;
    used.skins[node.skin] = true;
    for (int j : model.skins[node.skin].joints)
      if (in_range(j, nodes)) mark_with_ancestors(j, parent, moves_shown);
  }
  for (int a : playing) {
    if (!in_range(a, model.animations.size())) continue;
    for (const tinygltf::AnimationChannel& channel : model.animations[a].channels)
      if (in_range(channel.target_node, nodes) && moves_shown[channel.target_node]) used.animations[a] = true;
  }
  return used;
}

}  // namespace tessera
