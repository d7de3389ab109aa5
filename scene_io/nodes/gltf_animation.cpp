#include "scene_io/nodes/gltf_animation.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "scene_io/base/load_error.h"

namespace tessera {
namespace {

bool parse_path(const std::string& s, AnimationPath& path) {
  if (s == "translation") path = AnimationPath::Translation;
  else if (s == "rotation") path = AnimationPath::Rotation;
  else if (s == "scale") path = AnimationPath::Scale;
  else if (s == "weights") path = AnimationPath::Weights;
  else return false;
  return true;
}

Interpolation parse_interpolation(const std::string& s, const std::string& what, const std::string& file) {
  if (s.empty() || s == "LINEAR") return Interpolation::Linear;
  if (s == "STEP") return Interpolation::Step;
  if (s == "CUBICSPLINE") return Interpolation::CubicSpline;
  throw SceneLoadError(file, fmt::format("{} has interpolation '{}' (expected LINEAR, STEP or CUBICSPLINE)", what, s));
}

// The number of floats per key a channel's path needs (weights: as many as the output holds).
int path_width(AnimationPath path) {
  switch (path) {
    case AnimationPath::Rotation: return 4;
    case AnimationPath::Weights: return 0;
    default: return 3;
  }
}

AnimationChannel read_channel(const tinygltf::Model& model, const tinygltf::Animation& anim,
                              const tinygltf::AnimationChannel& src, const AccessorReader& reader,
                              const std::string& what, const std::string& file) {
  auto fail = [&](const std::string& problem) { throw SceneLoadError(file, what + " " + problem); };
  AnimationChannel c;
  c.node = src.target_node;
  if (c.node >= static_cast<int>(model.nodes.size()))
    fail(fmt::format("targets node {}, but the file has {}", c.node, count_of(model.nodes.size(), "node")));
  if (!parse_path(src.target_path, c.path))
    fail(fmt::format("has target path '{}' (expected translation, rotation, scale or weights)", src.target_path));
  if (c.path != AnimationPath::Weights && !model.nodes[c.node].matrix.empty())
    fail(fmt::format("animates the {} of node {}, which has a matrix (an animated node needs TRS)",
                     src.target_path, c.node));
  if (src.sampler < 0 || src.sampler >= static_cast<int>(anim.samplers.size()))
    fail(fmt::format("uses sampler {}, but the animation has {}", src.sampler,
                     count_of(anim.samplers.size(), "sampler")));
  const tinygltf::AnimationSampler& sampler = anim.samplers[src.sampler];
  c.interpolation = parse_interpolation(sampler.interpolation, what, file);
  const tinygltf::Accessor& input = reader.accessor(sampler.input, what + " input");
  if (input.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT || input.type != TINYGLTF_TYPE_SCALAR)
    fail(fmt::format("has input accessor {} of {} {}; keyframe times are FLOAT SCALAR", sampler.input,
                     gltf_component_type_name(input.componentType), gltf_type_name(input.type)));
  c.times = reader.floats(sampler.input, 1, what + " input");
  if (c.times.empty()) fail("has no keyframes");
  // Times without data are zeros, which the validator accepts: equal times are then allowed
  // (sampling never interpolates across an empty interval).
  const bool stored = input.bufferView >= 0 || input.sparse.isSparse;
  for (std::size_t k = 0; k < c.times.size(); ++k) {
    const bool increasing = k == 0 || c.times[k] > c.times[k - 1] || (!stored && c.times[k] == c.times[k - 1]);
    if (!std::isfinite(c.times[k]) || !increasing)
      fail(fmt::format("has keyframe times that are not finite and strictly increasing (key {})", k));
  }
  const int groups = c.interpolation == Interpolation::CubicSpline ? 3 : 1;
  const std::size_t keys = c.times.size() * groups;
  c.width = path_width(c.path);
  if (c.width == 0) {  // weights: one scalar per morph target and key
    const std::size_t count = reader.accessor(sampler.output, what + " output").count;
    if (count % keys != 0 || count == 0)
      fail(fmt::format("has {} output weights for {} keyframes", count, c.times.size()));
    c.width = static_cast<int>(count / keys);
    c.values = reader.floats(sampler.output, 1, what + " output");
  } else {
    c.values = reader.floats(sampler.output, c.width, what + " output");
  }
  if (c.values.size() != keys * c.width)
    fail(fmt::format("has {} output values for {} keyframes of {} each", c.values.size() / c.width,
                     c.times.size(), groups == 3 ? "three values (in-tangent, value, out-tangent)" : "one value"));
  return c;  // (the reader refuses non-finite values)
}

glm::quat to_quat(const float* xyzw) { return glm::quat(xyzw[3], xyzw[0], xyzw[1], xyzw[2]); }

// Spherical linear interpolation along the shorter arc (q and -q are one rotation).
glm::quat slerp_shortest(glm::quat a, glm::quat b, float u) {
  float d = glm::dot(a, b);
  if (d < 0.0f) {
    b = -b;
    d = -d;
  }
  if (d > 0.9995f) return glm::normalize(a + u * (b - a));  // nearly equal: the chord is the arc
  const float theta = std::acos(d), s = std::sin(theta);
  return (std::sin((1.0f - u) * theta) / s) * a + (std::sin(u * theta) / s) * b;
}


std::string animation_name(const tinygltf::Model& model, std::size_t a) {
  return model.animations[a].name.empty() ? fmt::format("animation {}", a) : model.animations[a].name;
}

}  // namespace

std::vector<Animation> animation_names(const tinygltf::Model& model) {
  std::vector<Animation> out(model.animations.size());
  for (std::size_t a = 0; a < out.size(); ++a) out[a].name = animation_name(model, a);
  return out;
}

Animation read_animation(const tinygltf::Model& model, std::size_t a, const AccessorReader& reader,
                         const std::string& file) {
  const tinygltf::Animation& src = model.animations[a];
  Animation anim;
  anim.name = animation_name(model, a);
  for (std::size_t i = 0; i < src.channels.size(); ++i) {
    if (src.channels[i].target_node < 0) continue;  // the specification: no node, no effect
    anim.channels.push_back(
        read_channel(model, src, src.channels[i], reader, fmt::format("animation {} channel {}", a, i), file));
  }
  for (std::size_t i = 0; i < anim.channels.size(); ++i) {
    const std::vector<float>& t = anim.channels[i].times;
    anim.start = i == 0 ? t.front() : std::min(anim.start, t.front());
    anim.end = i == 0 ? t.back() : std::max(anim.end, t.back());
  }
  return anim;
}

std::vector<int> choose_animations(const std::vector<Animation>& animations, const std::string& wanted,
                                   const std::string& file) {
  std::vector<int> playing;
  if (wanted == "none") return playing;
  if (wanted.empty() || wanted == "all") {
    for (std::size_t i = 0; i < animations.size(); ++i) playing.push_back(static_cast<int>(i));
    return playing;
  }
  for (std::size_t i = 0; i < animations.size(); ++i)
    if (animations[i].name == wanted) return {static_cast<int>(i)};
  const bool numeric = !wanted.empty() && wanted.size() < 9 && std::all_of(wanted.begin(), wanted.end(), ::isdigit);
  if (numeric && std::stoi(wanted) < static_cast<int>(animations.size())) return {std::stoi(wanted)};
  std::string names;
  for (std::size_t i = 0; i < animations.size(); ++i) names += fmt::format("{}{} '{}'", i ? ", " : "", i, animations[i].name);
  throw SceneLoadError(file, fmt::format("has no animation '{}' (it has {}{}{})", wanted,
                                         count_of(animations.size(), "animation"), animations.empty() ? "" : ": ", names));
}

std::vector<float> sample_channel(const AnimationChannel& c, float time) {
  const int w = c.width;
  const bool cubic = c.interpolation == Interpolation::CubicSpline;
  const std::size_t stride = cubic ? 3 * w : w, n = c.times.size();
  auto value = [&](std::size_t k) { return c.values.data() + k * stride + (cubic ? w : 0); };
  const bool rotation = c.path == AnimationPath::Rotation;
  auto result = [&](const float* v) {
    std::vector<float> r(v, v + w);
    if (rotation) {
      const glm::quat q = glm::normalize(to_quat(v));
      r = {q.x, q.y, q.z, q.w};
    }
    return r;
  };
  if (!(time > c.times.front())) return result(value(0));
  if (!(time < c.times.back())) return result(value(n - 1));
  const std::size_t k = static_cast<std::size_t>(std::upper_bound(c.times.begin(), c.times.end(), time) - c.times.begin()) - 1;
  const float td = c.times[k + 1] - c.times[k], u = (time - c.times[k]) / td;
  if (c.interpolation == Interpolation::Step) return result(value(k));
  std::vector<float> r(w);
  if (!cubic) {
    if (rotation) {
      const glm::quat q = slerp_shortest(glm::normalize(to_quat(value(k))), glm::normalize(to_quat(value(k + 1))), u);
      return result(&glm::vec4(q.x, q.y, q.z, q.w)[0]);
    }
    for (int i = 0; i < w; ++i) r[i] = value(k)[i] + u * (value(k + 1)[i] - value(k)[i]);
    return r;
  }
  // Hermite: p0 = v_k, m0 = td * out-tangent of k, p1 = v_k+1, m1 = td * in-tangent of k+1.
  const float u2 = u * u, u3 = u2 * u;
  const float h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
  const float* out_tangent = c.values.data() + k * stride + 2 * w;
  const float* in_tangent = c.values.data() + (k + 1) * stride;
  for (int i = 0; i < w; ++i)
    r[i] = h00 * value(k)[i] + h10 * td * out_tangent[i] + h01 * value(k + 1)[i] + h11 * td * in_tangent[i];
  return result(r.data());
}

std::vector<NodePose> pose_nodes(const std::vector<Animation>& animations, const std::vector<int>& playing,
                                 float time, std::size_t node_count) {
  std::vector<NodePose> poses(node_count);
  for (int a : playing)
    for (const AnimationChannel& c : animations[a].channels) {
      if (c.node < 0 || static_cast<std::size_t>(c.node) >= node_count) continue;
      NodePose& p = poses[c.node];
      const std::vector<float> v = sample_channel(c, time);
      switch (c.path) {
        case AnimationPath::Translation: p.translated = true, p.translation = {v[0], v[1], v[2]}; break;
        case AnimationPath::Rotation: p.rotated = true, p.rotation = to_quat(v.data()); break;
        case AnimationPath::Scale: p.scaled = true, p.scale = {v[0], v[1], v[2]}; break;
        case AnimationPath::Weights: p.weights = v; break;
      }
    }
  return poses;
}

}  // namespace tessera
