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
  build_over(positioned, 1);
}

LightTree::LightTree(const std::vector<LightBounds>& lights, int leaf_size) : leaf_of_(lights.size()) {
  std::vector<std::pair<LightBounds, std::uint32_t>> positioned;
  for (std::uint32_t i = 0; i < lights.size(); ++i)
    if (!lights[i].empty()) positioned.emplace_back(lights[i], i);
  build_over(positioned, leaf_size);
}

void LightTree::build_over(std::vector<std::pair<LightBounds, std::uint32_t>>& lights, int leaf_size) {
  in_tree_ = lights.size();
  if (lights.empty()) return;
  if (lights.size() >= (std::size_t(1) << 31)) throw std::length_error("too many lights for the light tree");
  nodes_.reserve(2 * lights.size() - 1);
  members_.reserve(lights.size());
  member_power_.reserve(lights.size());
  build(lights, 0, lights.size(), 0, 0, static_cast<std::size_t>(std::max(leaf_size, 1)));
}

// Splits at the median of the lights' centres along the longest axis of their box: a
// balanced tree (depth at most 31 here), whose way to each leaf the 64-bit trails hold.
// Returns the bounds of lights [begin, end), whose node is the next one made.
LightBounds LightTree::build(std::vector<std::pair<LightBounds, std::uint32_t>>& lights, std::size_t begin,
                             std::size_t end, std::uint64_t trail, int depth, std::size_t leaf_size) {
  const auto index = static_cast<std::uint32_t>(nodes_.size());
  nodes_.emplace_back();
  if (end - begin <= leaf_size) {
    LightBounds b = lights[begin].first;
    for (std::size_t i = begin + 1; i < end; ++i) b = LightBounds::merge(b, lights[i].first);
    nodes_[index] = {b.prepared(), static_cast<std::uint32_t>(members_.size()), static_cast<std::uint32_t>(end - begin)};
    for (std::size_t i = begin; i < end; ++i) {
      leaf_of_[lights[i].second] = {index, trail, depth, static_cast<std::uint32_t>(members_.size())};
      members_.push_back(lights[i].second);
      member_power_.push_back(lights[i].first.power);
    }
    return b;
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
  const LightBounds first = build(lights, begin, mid, trail, depth + 1, leaf_size);
  const auto second = static_cast<std::uint32_t>(nodes_.size());
  const LightBounds merged =
      LightBounds::merge(first, build(lights, mid, end, trail | (std::uint64_t(1) << depth), depth + 1, leaf_size));
  nodes_[index] = {merged.prepared(), second, 0};
  return merged;
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
  while (nodes_[node].count == 0) {
    // Which child the walk takes is known only after both bounds' importance: the
    // grandchildren are fetched meanwhile, whichever it is.
    const Node& second = nodes_[nodes_[node].child];
    if (nodes_[node + 1].count == 0) __builtin_prefetch(&nodes_[nodes_[node + 1].child]);
    if (second.count == 0) __builtin_prefetch(&nodes_[second.child]);
    const float first = first_child_probability(node, p, n);
    if (first < 0.0f) return {};
    // Without a branch on the choice (half of them would be mispredicted, each after the
    // whole importance computation).
    const bool take_first = u < first;
    const float branch = take_first ? first : 1.0f - first;
    u = std::min((take_first ? u : u - first) / branch, 0x1.fffffep-1f);
    pmf *= branch;
    node = take_first ? node + 1 : nodes_[node].child;
  }
  const Node& leaf = nodes_[node];
  if (leaf.count == 1) return {members_[leaf.child], pmf};
  // In a leaf of several: by power, the share of each its probability.
  const float total = leaf.bounds.power, target = u * total;
  std::uint32_t k = leaf.child, last = leaf.child + leaf.count - 1;
  float below = 0.0f;
  for (; k < last; ++k) {
    below += member_power_[k];
    if (target < below) break;
  }
  return {members_[k], pmf * (member_power_[k] / total)};
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
  if (nodes_[node].count == 1) return pmf;
  return pmf * (member_power_[leaf.member] / nodes_[node].bounds.power);
}

}  // namespace tessera
