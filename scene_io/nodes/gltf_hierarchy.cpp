#include "scene_io/nodes/gltf_hierarchy.h"

#include <fmt/format.h>

#include "scene_io/base/load_error.h"

namespace tessera {

std::vector<int> check_node_hierarchy(const tinygltf::Model& model, const std::string& file) {
  auto fail = [&](const std::string& problem) { throw SceneLoadError(file, problem); };
  const int n = static_cast<int>(model.nodes.size());
  std::vector<int> parent(n, -1);
  for (int i = 0; i < n; ++i)
    for (int c : model.nodes[i].children) {
      if (c < 0 || c >= n)
        fail(fmt::format("node {} has child {}, but the file has {}", i, c, count_of(n, "node")));
      if (c == i) fail(fmt::format("node {} lists itself as a child", i));
      if (parent[c] == i) fail(fmt::format("node {} lists child {} twice", i, c));
      if (parent[c] >= 0)
        fail(fmt::format("node {} is a child of both node {} and node {}; a node may have only "
                         "one parent",
                         c, parent[c], i));
      parent[c] = i;
    }
  // With one parent each, a cycle shows up as a walk towards the root that meets itself.
  enum : char { kNew, kOnWalk, kDone };
  std::vector<char> state(n, kNew);
  std::vector<int> walk;
  for (int i = 0; i < n; ++i) {
    walk.clear();
    int k = i;
    for (; k >= 0 && state[k] == kNew; k = parent[k]) {
      state[k] = kOnWalk;
      walk.push_back(k);
    }
    if (k >= 0 && state[k] == kOnWalk)
      fail(fmt::format("node {} is its own ancestor (the node hierarchy has a cycle)", k));
    for (int w : walk) state[w] = kDone;
  }
  return parent;
}

std::vector<int> scene_roots(const tinygltf::Model& model, int scene, const std::vector<int>& parent,
                             const std::string& file) {
  const int n = static_cast<int>(model.nodes.size());
  std::vector<int> roots;
  if (scene < 0) {
    for (int i = 0; i < n; ++i)
      if (parent[i] < 0) roots.push_back(i);
    return roots;
  }
  std::vector<bool> listed(n, false);
  for (int r : model.scenes[scene].nodes) {
    auto fail = [&](const std::string& problem) {
      throw SceneLoadError(file, fmt::format("scene {} {}", scene, problem));
    };
    if (r < 0 || r >= n) fail(fmt::format("refers to node {}, but the file has {}", r, count_of(n, "node")));
    if (parent[r] >= 0)
      fail(fmt::format("lists node {} as a root, but it is a child of node {}", r, parent[r]));
    if (listed[r]) fail(fmt::format("lists node {} twice", r));
    listed[r] = true;
    roots.push_back(r);
  }
  return roots;
}

}  // namespace tessera
