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
  members_.reserve(lights.size());
  member_power_.reserve(lights.size());
  leaf_power_.reserve(lights.size());
  std::vector<Binary> binary;
  binary.reserve(2 * lights.size() - 1);
  build(lights, 0, lights.size(), static_cast<std::size_t>(std::max(leaf_size, 1)), binary);
  if (binary[0].count > 0) {  // one leaf: a root of one child
    nodes_.emplace_back();
    nodes_[0].bounds.set(0, binary[0].bounds);
    nodes_[0].child[0] = binary[0].begin;
    nodes_[0].count[0] = binary[0].count;
    for (std::uint32_t m = binary[0].begin; m < binary[0].begin + binary[0].count; ++m) leaf_of_[members_[m]] = {0, 1, m};
    return;
  }
  collapse(binary, 0, 0, 0);
}

// Splits at the median of the lights' centres along the longest axis of their box: a
// balanced tree (at most 31 binary levels here, so at most 31 levels of four children,
// whose two-bit ways the 64-bit trails hold). Returns the index of the subtree's root.
std::uint32_t LightTree::build(std::vector<std::pair<LightBounds, std::uint32_t>>& lights, std::size_t begin,
                               std::size_t end, std::size_t leaf_size, std::vector<Binary>& binary) {
  const auto index = static_cast<std::uint32_t>(binary.size());
  binary.emplace_back();
  if (end - begin <= leaf_size) {
    Binary leaf;
    leaf.bounds = lights[begin].first;
    for (std::size_t i = begin + 1; i < end; ++i) leaf.bounds = LightBounds::merge(leaf.bounds, lights[i].first);
    leaf.begin = static_cast<std::uint32_t>(members_.size());
    leaf.count = static_cast<std::uint32_t>(end - begin);
    for (std::size_t i = begin; i < end; ++i) {
      members_.push_back(lights[i].second);
      member_power_.push_back(lights[i].first.power);
      leaf_power_.push_back(leaf.bounds.power);
    }
    binary[index] = leaf;
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
  const std::uint32_t first = build(lights, begin, mid, leaf_size, binary);
  const std::uint32_t second = build(lights, mid, end, leaf_size, binary);
  Binary node;
  node.bounds = LightBounds::merge(binary[first].bounds, binary[second].bounds);
  node.first = first, node.second = second;
  binary[index] = node;
  return index;
}

std::uint32_t LightTree::collapse(const std::vector<Binary>& binary, std::uint32_t b, std::uint64_t trail, int depth) {
  const auto index = static_cast<std::uint32_t>(nodes_.size());
  nodes_.emplace_back();
  std::uint32_t slots[4];
  int count = 0;
  for (std::uint32_t c : {binary[b].first, binary[b].second}) {
    if (binary[c].count > 0) {
      slots[count++] = c;
    } else {
      slots[count++] = binary[c].first;
      slots[count++] = binary[c].second;
    }
  }
  for (int k = 0; k < count; ++k) {
    const Binary& c = binary[slots[k]];
    const std::uint64_t way = trail | (std::uint64_t(k) << (2 * depth));
    nodes_[index].bounds.set(k, c.bounds);
    if (c.count > 0) {
      nodes_[index].child[k] = c.begin;
      nodes_[index].count[k] = c.count;
      for (std::uint32_t m = c.begin; m < c.begin + c.count; ++m) leaf_of_[members_[m]] = {way, depth + 1, m};
    } else {
      const std::uint32_t child = collapse(binary, slots[k], way, depth + 1);
      nodes_[index].child[k] = child;  // nodes_ may have moved: indexed again
    }
  }
  return index;
}

bool LightTree::used(LightTreeUse use) const {
  if (empty() || use == LightTreeUse::Off) return false;
  return use == LightTreeUse::On || size() > kLightTreeAutoMin;
}

bool LightTree::child_importance(const Node& node, const vec3& p, const vec3& n, float imp[4], float& total) const {
  node.bounds.importance(p, n, imp);
  total = (imp[0] + imp[1]) + (imp[2] + imp[3]);
  if (!(total > 0.0f)) return false;
  if (!std::isfinite(total)) {
    total = 0.0f;
    for (int k = 0; k < 4; ++k) total += imp[k] = std::isinf(imp[k]) ? 1.0f : 0.0f;
    if (!(total > 0.0f)) return false;
  }
  return true;
}

LightTree::Choice LightTree::sample(const vec3& p, const vec3& n, float u) const {
  if (empty()) return {};
  std::uint32_t node = 0;
  float pmf = 1.0f;
  for (;;) {
    const Node& here = nodes_[node];
    float imp[4], total;
    if (!child_importance(here, p, n, imp, total)) return {};
    // The child whose share of [0, total) holds u x total, u made uniform again within it;
    // counted without branches (a mispredicted one costs as much as the importance), a child
    // of no importance never (its share is empty), but for rounding at the very end.
    const float target = u * total;
    const float below[4] = {0.0f, imp[0], imp[0] + imp[1], (imp[0] + imp[1]) + imp[2]};
    int k = int(target >= below[1]) + int(target >= below[2]) + int(target >= below[3]);
    while (!(imp[k] > 0.0f)) k = (k + 3) & 3;  // rounding past the last: the last that has a share
    u = std::min(std::max((target - below[k]) / imp[k], 0.0f), 0x1.fffffep-1f);
    pmf *= imp[k] / total;
    if (here.count[k] == 0) {
      node = here.child[k];
      continue;
    }
    const std::uint32_t first = here.child[k], count = here.count[k];
    if (count == 1) return {members_[first], pmf};
    // In a leaf of several: by power, the share of each its probability.
    const float leaf_power = leaf_power_[first], leaf_target = u * leaf_power;
    std::uint32_t m = first;
    float sum = 0.0f;
    for (; m + 1 < first + count; ++m) {
      sum += member_power_[m];
      if (leaf_target < sum) break;
    }
    return {members_[m], pmf * (member_power_[m] / leaf_power)};
  }
}

float LightTree::pmf(const vec3& p, const vec3& n, std::uint32_t light) const {
  if (light >= leaf_of_.size() || leaf_of_[light].depth < 0) return 0.0f;
  const Leaf& leaf = leaf_of_[light];
  std::uint32_t node = 0, count = 0;
  float pmf = 1.0f;
  for (int d = 0; d < leaf.depth; ++d) {
    const Node& here = nodes_[node];
    float imp[4], total;
    if (!child_importance(here, p, n, imp, total)) return 0.0f;
    const int k = static_cast<int>((leaf.trail >> (2 * d)) & 3u);
    if (!(imp[k] > 0.0f)) return 0.0f;
    pmf *= imp[k] / total;
    node = here.child[k], count = here.count[k];
  }
  if (count == 1) return pmf;
  return pmf * (member_power_[leaf.member] / leaf_power_[leaf.member]);
}

}  // namespace tessera
