#include "renderer/guiding/direction_tree.h"

#include <algorithm>
#include <cmath>

namespace tessera {

vec2 direction_to_square(const vec3& d) {
  const float z = std::clamp(d.z, -1.0f, 1.0f);
  float phi = std::atan2(d.y, d.x) * (0.5f / kPi);
  if (phi < 0.0f) phi += 1.0f;
  return {std::clamp(0.5f * (z + 1.0f), 0.0f, 1.0f), std::min(phi, std::nextafter(1.0f, 0.0f))};
}

vec3 square_to_direction(const vec2& p) {
  const float z = 2.0f * p.x - 1.0f, r = std::sqrt(std::max(0.0f, 1.0f - z * z)), phi = 2.0f * kPi * p.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

DirectionTree::DirectionTree() : children_(1, {0, 0, 0, 0}), energy_(1, 0.0) {}

namespace {
// The child of a node's square that holds p (in the node's own [0, 1)^2), and p in the child's.
int quadrant(vec2& p) {
  const int cx = p.x >= 0.5f, cy = p.y >= 0.5f;
  p = {std::min(p.x * 2.0f - cx, std::nextafter(1.0f, 0.0f)), std::min(p.y * 2.0f - cy, std::nextafter(1.0f, 0.0f))};
  return cx + 2 * cy;
}
}  // namespace

std::uint32_t DirectionTree::leaf_of(vec2 p) const {
  std::uint32_t node = 0;
  while (!is_leaf(node)) node = children_[node][quadrant(p)];
  return node;
}

void DirectionTree::set_energy(const std::vector<double>& leaf_energy) {
  energy_.assign(children_.size(), 0.0);
  // Children always come after their parent: a backward pass sums the leaves up.
  for (std::size_t n = children_.size(); n-- > 0;) {
    if (is_leaf(static_cast<std::uint32_t>(n))) energy_[n] = std::max(0.0, leaf_energy[n]);
    else
      for (std::uint32_t c : children_[n]) energy_[n] += energy_[c];
  }
}

vec2 DirectionTree::sample(vec2 u_in, float& pdf) const {
  // In double: each level stretches u by 1 / (a child's share), and a float's 24 bits would
  // be spent within a few levels, leaving a lattice of directions in a deep leaf.
  double ux = u_in.x, uy = u_in.y, ox = 0.0, oy = 0.0, size = 1.0, density = 1.0;
  std::uint32_t node = 0;
  while (!is_leaf(node)) {
    const auto& c = children_[node];
    const double e[4] = {energy_[c[0]], energy_[c[1]], energy_[c[2]], energy_[c[3]]};
    const double total = e[0] + e[1] + e[2] + e[3];
    // The column (x) by its two children's share, then the row within it: u stays uniform.
    const double left = (e[0] + e[2]) / total;
    int cx = 0;
    if (ux < left) ux /= left;
    else cx = 1, ux = (ux - left) / (1.0 - left);
    const double low = e[cx] / (e[cx] + e[cx + 2]);
    int cy = 0;
    if (uy < low) uy /= low;
    else cy = 1, uy = (uy - low) / (1.0 - low);
    ux = std::min(ux, 1.0), uy = std::min(uy, 1.0);
    const int q = cx + 2 * cy;
    density *= 4.0 * e[q] / total;
    size *= 0.5;
    ox += size * cx, oy += size * cy;
    node = c[q];
  }
  pdf = static_cast<float>(density);
  const float most = std::nextafter(1.0f, 0.0f);
  return {std::min(static_cast<float>(ox + size * ux), most), std::min(static_cast<float>(oy + size * uy), most)};
}

float DirectionTree::pdf(vec2 p) const {
  std::uint32_t node = 0;
  double density = 1.0;
  while (!is_leaf(node)) {
    const auto& c = children_[node];
    const std::uint32_t child = c[quadrant(p)];
    if (!(energy_[child] > 0.0)) return 0.0f;  // nothing learnt there (and below it)
    density *= 4.0 * energy_[child] / energy_[node];
    node = child;
  }
  return static_cast<float>(density);
}

void DirectionTree::refine_into(DirectionTree& out, std::uint32_t out_node, std::uint32_t node, bool real,
                                double energy, double threshold, int depth, int max_depth) const {
  if (!(energy > threshold) || depth >= max_depth) return;
  const std::uint32_t first = static_cast<std::uint32_t>(out.children_.size());
  out.children_.resize(first + 4, {0, 0, 0, 0});
  for (std::uint32_t q = 0; q < 4; ++q) out.children_[out_node][q] = first + q;
  const bool has_children = real && !is_leaf(node);
  for (std::uint32_t q = 0; q < 4; ++q) {
    const std::uint32_t child = has_children ? children_[node][q] : node;
    const double e = has_children ? energy_[child] : energy / 4.0;
    refine_into(out, first + q, child, has_children, e, threshold, depth + 1, max_depth);
  }
}

DirectionTree DirectionTree::refined(double fraction, int max_depth) const {
  DirectionTree out;
  refine_into(out, 0, 0, true, total(), fraction * total(), 0, max_depth);
  out.energy_.assign(out.children_.size(), 0.0);
  return out;
}

}  // namespace tessera
