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
  // Up to four children (each a node, or a leaf of lights) with their bounds side by side: one
  // SSE pass gives the four importances. The tree is built binary (median splits), then read
  // two levels at a time: a node's children are its binary node's grandchildren (a leaf
  // child stays itself), so the walk has half the levels.
  struct alignas(64) Node {
    LightBounds4 bounds;
    std::uint32_t child[4] = {0, 0, 0, 0};  // a node's index; a leaf's first place in members_
    std::uint32_t count[4] = {0, 0, 0, 0};  // a leaf's lights; 0: a node, or no child (no power)
  };
  struct Binary {  // the tree as built
    LightBounds bounds;
    std::uint32_t first = 0, second = 0;  // children (interior)
    std::uint32_t begin = 0, count = 0;  // a leaf's lights in members_ (count > 0)
  };
  std::uint32_t build(std::vector<std::pair<LightBounds, std::uint32_t>>& lights, std::size_t begin, std::size_t end,
                      std::size_t leaf_size, std::vector<Binary>& binary);
  void build_over(std::vector<std::pair<LightBounds, std::uint32_t>>& lights, int leaf_size);
  // Makes the node whose children are those of binary node `b` and below it; `trail`, `depth`:
  // the way to it.
  std::uint32_t collapse(const std::vector<Binary>& binary, std::uint32_t b, std::uint64_t trail, int depth);
  // The children's importance at p (imp) and their sum; false: none can reach p. Where some
  // are infinite, those share the choice evenly.
  bool child_importance(const Node& node, const vec3& p, const vec3& n, float imp[4], float& total) const;

  std::vector<Node> nodes_;
  std::vector<std::uint32_t> directional_;
  std::vector<std::uint32_t> members_;  // the leaves' lights, each leaf's together
  std::vector<float> member_power_;  // their powers, in the same order
  std::vector<float> leaf_power_;  // in the same order: the power of the member's whole leaf
  // Per scene light: the way to its leaf (two bits per level: which of four children) and
  // its place in members_.
  struct Leaf {
    std::uint64_t trail = 0;
    int depth = -1;  // levels; -1: not in the tree
    std::uint32_t member = 0;
  };
  std::vector<Leaf> leaf_of_;
  std::size_t in_tree_ = 0;
};

}  // namespace tessera
