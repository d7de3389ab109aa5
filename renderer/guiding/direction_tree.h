// The incident radiance at one region of space over the sphere of directions, as a quadtree
// (Müller et al. 2017, "Practical Path Guiding"): the sphere maps onto the unit square with
// equal areas (cylindrical: z = 2 s - 1, phi = 2 pi t), each node splits its square into four,
// and each node holds the energy arriving through it. Sampling walks down choosing children
// in proportion to their energy: the density is high where much light arrives.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "renderer/util/math.h"

namespace tessera {

// A unit direction's point of the square, and back.
vec2 direction_to_square(const vec3& d);
vec3 square_to_direction(const vec2& p);

class DirectionTree {
 public:
  DirectionTree();  // one node: uniform over the sphere

  std::size_t size() const { return children_.size(); }  // nodes
  bool is_leaf(std::uint32_t node) const { return children_[node][0] == 0; }
  const std::array<std::uint32_t, 4>& children(std::uint32_t node) const { return children_[node]; }
  // The leaf whose square holds p.
  std::uint32_t leaf_of(vec2 p) const;

  // Gives each node its energy from its leaves' (leaf_energy[n] for leaf n; inner nodes'
  // entries are ignored): sums up the tree.
  void set_energy(const std::vector<double>& leaf_energy);
  double total() const { return energy_[0]; }
  double energy(std::uint32_t node) const { return energy_[node]; }

  // A point of the square and its density over the square (total() > 0).
  vec2 sample(vec2 u, float& pdf) const;
  float pdf(vec2 p) const;

  // The structure for the next round of learning, from this tree's energies (Müller et al.:
  // a node is split while it holds more than `fraction` of the total, down to max_depth;
  // nodes below it are merged). A leaf split anew counts a quarter of its energy per child.
  DirectionTree refined(double fraction, int max_depth) const;

 private:
  void refine_into(DirectionTree& out, std::uint32_t out_node, std::uint32_t node, bool real, double energy,
                   double threshold, int depth, int max_depth) const;
  std::vector<std::array<std::uint32_t, 4>> children_;  // 0: a leaf (the root is never a child)
  std::vector<double> energy_;
};

}  // namespace tessera
