#include "renderer/guiding/space_tree.h"

#include <algorithm>

namespace tessera {

SpaceTree::SpaceTree(const Bounds3& box) : box_(box), nodes_(1) {
  const vec3 size = glm::max(box.diagonal(), vec3(1e-20f));
  inv_size_ = 1.0f / size;
}

std::uint32_t SpaceTree::region_of(const vec3& p) const {
  // In the box's unit cube: each level halves one axis, so the point scales by 2 on it.
  vec3 q = glm::clamp((p - box_.lo) * inv_size_, vec3(0.0f), vec3(1.0f));
  std::uint32_t node = 0;
  int axis = 0;
  while (nodes_[node].child[0] != 0) {
    const int side = q[axis] >= 0.5f;
    q[axis] = q[axis] * 2.0f - static_cast<float>(side);
    node = nodes_[node].child[side];
    axis = (axis + 1) % 3;
  }
  return nodes_[node].region;
}

void SpaceTree::split_into(SpaceTree& out, std::uint32_t out_node, std::uint32_t node, double count, double most,
                           int depth, int max_depth, std::uint32_t region, const std::vector<std::uint64_t>& counts,
                           std::vector<std::uint32_t>& from) const {
  const Node& n = nodes_[node];
  const bool inner = n.child[0] != 0;
  // count < 0: a leaf of this tree reached, its count not read yet (below it, the halves').
  if (!inner && count < 0.0) region = n.region, count = static_cast<double>(counts[region]);
  // An inner node of this tree stays split (its regions are judged at its leaves); a leaf
  // splits while it would hold too much.
  if (inner || (count > most && depth < max_depth)) {
    const std::uint32_t first = static_cast<std::uint32_t>(out.nodes_.size());
    out.nodes_.resize(first + 2);
    out.nodes_[out_node].child[0] = first, out.nodes_[out_node].child[1] = first + 1;
    for (int side = 0; side < 2; ++side) {
      if (inner) split_into(out, first + side, n.child[side], -1.0, most, depth + 1, max_depth, 0, counts, from);
      else split_into(out, first + side, node, count / 2.0, most, depth + 1, max_depth, region, counts, from);
    }
    return;
  }
  out.nodes_[out_node].region = static_cast<std::uint32_t>(from.size());
  from.push_back(region);
}

SpaceTree SpaceTree::split(const std::vector<std::uint64_t>& counts, double most, std::vector<std::uint32_t>& from,
                           int max_depth) const {
  SpaceTree out(box_);
  from.clear();
  split_into(out, 0, 0, -1.0, most, 0, max_depth, 0, counts, from);
  out.region_count_ = from.size();
  return out;
}

}  // namespace tessera
