// The regions of space a path guide learns in: a binary tree over the scene's box, each node
// halving its box across x, y, z in turn (Müller et al. 2017). A region is split where many
// path vertices fell, so the guide is fine where the camera looks and coarse elsewhere.
#pragma once

#include <cstdint>
#include <vector>

#include "renderer/description/scene.h"
#include "renderer/util/math.h"

namespace tessera {

class SpaceTree {
 public:
  SpaceTree() : SpaceTree(Bounds3{vec3(0.0f), vec3(1.0f)}) {}
  explicit SpaceTree(const Bounds3& box);  // one region: the box

  std::size_t regions() const { return region_count_; }
  // The region of a point (outside the box: the region of the nearest point in it).
  std::uint32_t region_of(const vec3& p) const;

  // A tree whose regions each held at most `most` of the `counts` (one per region), assuming
  // a region's count halves with each split; from[r] is the region of this tree that new
  // region r lies in. At most max_depth levels.
  SpaceTree split(const std::vector<std::uint64_t>& counts, double most, std::vector<std::uint32_t>& from,
                  int max_depth = 30) const;

 private:
  struct Node {
    std::uint32_t child[2] = {0, 0};  // 0: a leaf (the root is never a child)
    std::uint32_t region = 0;  // a leaf's
  };
  void split_into(SpaceTree& out, std::uint32_t out_node, std::uint32_t node, double count, double most, int depth,
                  int max_depth, std::uint32_t region, const std::vector<std::uint64_t>& counts,
                  std::vector<std::uint32_t>& from) const;
  Bounds3 box_;
  vec3 inv_size_{1.0f};
  std::vector<Node> nodes_;
  std::size_t region_count_ = 1;
};

}  // namespace tessera
