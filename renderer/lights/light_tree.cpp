#include "renderer/lights/light_tree.h"

#include <algorithm>
#include <stdexcept>

#include "renderer/util/named_enum.h"

namespace tessera {

const std::vector<std::string>& light_tree_use_names() {
  static const std::vector<std::string> names{"auto", "on", "off"};
  return names;
}

LightTreeUse parse_light_tree_use(const std::string& name) {
  return parse_enum<LightTreeUse>(light_tree_use_names(), name, "light tree use");
}

namespace {

// A point or spot light's bounds: where it can be while the shutter is open, and its cone.
LightBounds bounds_of(const PunctualLight& light) {
  LightBounds b;
  b.lo = b.hi = light.motion.empty() ? light.position : vec3(light.light_to_world[3]);
  for (const glm::mat4& step : light.motion) {
    b.lo = glm::min(b.lo, vec3(step[3]));
    b.hi = glm::max(b.hi, vec3(step[3]));
  }
  b.power = luminance(light.color * light.intensity);
  if (light.type == PunctualLight::Type::Spot && light.motion.empty()) {
    b.axis = glm::normalize(light.direction);
    b.cos_spread = 1.0f;
    b.cos_emit = std::cos(std::min(light.outer_cone_angle, kPi));
  } else {  // a point light, or a spot that turns: any way
    b.cos_spread = -1.0f;
    b.cos_emit = 0.0f;
  }
  return b;
}

}  // namespace

LightTree::LightTree(const std::vector<PunctualLight>& lights) : leaf_of_(lights.size()) {
  std::vector<std::pair<LightBounds, std::uint32_t>> positioned;
  for (std::uint32_t i = 0; i < lights.size(); ++i) {
    if (lights[i].type == PunctualLight::Type::Directional) {
      directional_.push_back(i);
      continue;
    }
    const LightBounds b = bounds_of(lights[i]);
    if (!b.empty()) positioned.emplace_back(b, i);  // a light of no power is never chosen
  }
  in_tree_ = positioned.size();
  if (positioned.empty()) return;
  if (positioned.size() >= (std::size_t(1) << 62)) throw std::length_error("too many lights for the light tree");
  nodes_.reserve(2 * positioned.size() - 1);
  build(positioned, 0, positioned.size(), 0, 0);
}

// Splits at the median of the lights' centres along the longest axis of their box: a
// balanced tree, whose depth (at most 62 here) the 64-bit trails hold.
std::uint32_t LightTree::build(std::vector<std::pair<LightBounds, std::uint32_t>>& lights, std::size_t begin,
                               std::size_t end, std::uint64_t trail, int depth) {
  const auto index = static_cast<std::uint32_t>(nodes_.size());
  nodes_.emplace_back();
  if (end - begin == 1) {
    nodes_[index] = {lights[begin].first, lights[begin].second, true};
    leaf_of_[lights[begin].second] = {index, trail, depth};
    return index;
  }
  vec3 lo(std::numeric_limits<float>::infinity()), hi(-std::numeric_limits<float>::infinity());
  for (std::size_t i = begin; i < end; ++i) {
    const vec3 c = 0.5f * (lights[i].first.lo + lights[i].first.hi);
    lo = glm::min(lo, c);
    hi = glm::max(hi, c);
  }
  const vec3 extent = hi - lo;
  const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
  const std::size_t mid = begin + (end - begin) / 2;
  // Ties broken by the light's index, so the tree is the same on every machine and run.
  std::nth_element(lights.begin() + begin, lights.begin() + mid, lights.begin() + end, [axis](const auto& a, const auto& b) {
    const float ca = a.first.lo[axis] + a.first.hi[axis], cb = b.first.lo[axis] + b.first.hi[axis];
    return ca < cb || (ca == cb && a.second < b.second);
  });
  build(lights, begin, mid, trail, depth + 1);
  const std::uint32_t second = build(lights, mid, end, trail | (std::uint64_t(1) << depth), depth + 1);
  const LightBounds merged = LightBounds::merge(nodes_[index + 1].bounds, nodes_[second].bounds);
  nodes_[index] = {merged, second, false};
  return index;
}

bool LightTree::used(LightTreeUse use) const {
  if (empty() || use == LightTreeUse::Off) return false;
  return use == LightTreeUse::On || size() > kLightTreeAutoMin;
}

float LightTree::first_child_probability(std::uint32_t node, const vec3& p, const vec3& n) const {
  const float a = nodes_[node + 1].bounds.importance(p, n), b = nodes_[nodes_[node].child].bounds.importance(p, n);
  if (!(a + b > 0.0f)) return -1.0f;
  if (!std::isfinite(a + b)) return std::isfinite(a) ? 0.0f : std::isfinite(b) ? 1.0f : 0.5f;
  return a / (a + b);
}

LightTree::Choice LightTree::sample(const vec3& p, const vec3& n, float u) const {
  if (empty()) return {};
  std::uint32_t node = 0;
  float pmf = 1.0f;
  while (!nodes_[node].leaf) {
    const float first = first_child_probability(node, p, n);
    if (first < 0.0f) return {};
    if (u < first) {
      u = std::min(u / first, 0x1.fffffep-1f);
      pmf *= first;
      node = node + 1;
    } else {
      u = std::min((u - first) / (1.0f - first), 0x1.fffffep-1f);
      pmf *= 1.0f - first;
      node = nodes_[node].child;
    }
  }
  return {nodes_[node].child, pmf};
}

float LightTree::pmf(const vec3& p, const vec3& n, std::uint32_t light) const {
  if (light >= leaf_of_.size() || leaf_of_[light].depth < 0) return 0.0f;
  const Leaf& leaf = leaf_of_[light];
  std::uint32_t node = 0;
  float pmf = 1.0f;
  for (int d = 0; d < leaf.depth; ++d) {
    const float first = first_child_probability(node, p, n);
    if (first < 0.0f) return 0.0f;
    const bool second = (leaf.trail >> d) & 1u;
    pmf *= second ? 1.0f - first : first;
    node = second ? nodes_[node].child : node + 1;
  }
  return pmf;
}

}  // namespace tessera
