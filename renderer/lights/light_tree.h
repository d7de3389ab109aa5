// Many-light sampling: a binary tree of LightBounds over lights, walked from the root to one
// light, each step choosing a child in proportion to its importance at the shading point
// (Conty Estevez and Kulla 2018; pbrt-v4's BVHLightSampler). A path then traces one shadow ray
// to one light, divided by the probability of choosing it. One tree is over the point and spot
// lights (directional lights are not in it: they are always sampled, each), where sampling
// every light traces one ray per light; another over the emissive triangles (AreaLights), where
// the choice by power alone ignores where the shading point is.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "renderer/description/scene.h"
#include "renderer/lights/light_bounds.h"

namespace tessera {

// When a path samples one punctual light from the tree instead of each of them, and chooses
// its emissive triangle by the tree instead of by power alone.
enum class LightTreeUse : std::uint8_t { Auto, On, Off };
const std::vector<std::string>& light_tree_use_names();  // "auto", "on", "off"
LightTreeUse parse_light_tree_use(const std::string& name);  // throws std::invalid_argument
// Auto: with more than this many point and spot lights (a shadow ray each per vertex).
constexpr std::size_t kLightTreeAutoMin = 8;

class LightTree {
 public:
  LightTree() = default;
  // Over the scene's point and spot lights; a light that moves is bounded over its motion steps.
  explicit LightTree(const std::vector<PunctualLight>& lights);
  // Over lights of the given bounds (an empty one, of no power, is left out: never chosen),
  // with up to `leaf_size` lights in a leaf, one chosen there in proportion to its power.
  explicit LightTree(const std::vector<LightBounds>& lights, int leaf_size = 1);

  bool empty() const { return nodes_.empty(); }
  std::size_t size() const { return in_tree_; }  // lights in the tree
  // Whether `use` has the path sample the tree (Auto: more than kLightTreeAutoMin lights).
  bool used(LightTreeUse use) const;
  const std::vector<std::uint32_t>& directional() const { return directional_; }  // outside the tree

  struct Choice {
    std::uint32_t light = 0;  // index into the scene's lights
    float pmf = 0.0f;  // 0: no light can reach the point
  };
  // One light for a point p with surface normal n (0: none), from one uniform number.
  Choice sample(const vec3& p, const vec3& n, float u) const;
  // The probability sample() chooses `light` (a scene light index) at p: the product of the
  // branch probabilities on its way from the root (and in a leaf of several, its share of the
  // leaf's power). 0 for a light outside the tree.
  float pmf(const vec3& p, const vec3& n, std::uint32_t light) const;

 private:
  struct alignas(64) Node {  // one cache line
    LightBounds::Prepared bounds;
    std::uint32_t child = 0;  // interior: the second child (the first follows the node); leaf: its first member
    std::uint32_t count = 0;  // lights in a leaf; 0: interior
  };
  void build_over(std::vector<std::pair<LightBounds, std::uint32_t>>& lights, int leaf_size);
  LightBounds build(std::vector<std::pair<LightBounds, std::uint32_t>>& lights, std::size_t begin, std::size_t end,
                    std::uint64_t trail, int depth, std::size_t leaf_size);
  // The probability of the first child of interior node `node` at p (NaN-free; -1: neither can
  // reach p).
  float first_child_probability(std::uint32_t node, const vec3& p, const vec3& n) const;

  std::vector<Node> nodes_;
  std::vector<std::uint32_t> directional_;
  std::vector<std::uint32_t> members_;  // the leaves' lights, each leaf's together
  std::vector<float> member_power_;  // their powers, in the same order
  // Per scene light: its leaf's node and the way to it (bit d: the second child at depth d).
  struct Leaf {
    std::uint32_t node = 0;
    std::uint64_t trail = 0;
    int depth = -1;  // -1: not in the tree
    std::uint32_t member = 0;  // its place in members_
  };
  std::vector<Leaf> leaf_of_;
  std::size_t in_tree_ = 0;
};

}  // namespace tessera
