// glTF 2.0 animations, read once and evaluated at any time: each channel drives one node's
// translation, rotation, scale or morph weights through a sampler of keyframes, interpolated
// STEP, LINEAR (rotations by spherical linear interpolation) or CUBICSPLINE (Hermite, the
// specification's Appendix C), and held at its first and last key outside their range.
// The loader poses the node hierarchy with it, so the renderer sees a scene at one time.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <tiny_gltf.h>

#include "scene_io/base/gltf_accessor.h"

namespace tessera {

enum class AnimationPath : std::uint8_t { Translation, Rotation, Scale, Weights };
enum class Interpolation : std::uint8_t { Step, Linear, CubicSpline };

struct AnimationChannel {
  int node = -1;
  AnimationPath path = AnimationPath::Translation;
  Interpolation interpolation = Interpolation::Linear;
  std::vector<float> times;  // seconds, strictly increasing (or all zero: an input accessor without data)
  // `width` floats per key (3, 4 or the morph target count); CUBICSPLINE stores three such
  // groups per key: in-tangent, value, out-tangent.
  std::vector<float> values;
  int width = 0;
};

struct Animation {
  std::string name;  // the file's, else "animation N"
  std::vector<AnimationChannel> channels;
  float start = 0.0f, end = 0.0f;  // the first and last key time over its channels
};

// Animation `index` of the file. Throws SceneLoadError for a channel or sampler the
// specification forbids (indices out of range, times not increasing, output counts that do
// not match the inputs, a channel on a node given by a matrix).
Animation read_animation(const tinygltf::Model& model, std::size_t index, const AccessorReader& reader,
                         const std::string& file);

// Every animation of the file by name alone ("animation N" when it has none), without channels.
std::vector<Animation> animation_names(const tinygltf::Model& model);

// Which animations play: `wanted` by name, else index, "all" or empty for every one (as
// viewers play them), "none" for none. Returns their indices; throws SceneLoadError for a
// name or index the file does not have, listing the animations it has.
std::vector<int> choose_animations(const std::vector<Animation>& animations, const std::string& wanted,
                                   const std::string& file);

// One node's animated local transform; what no channel drives keeps the node's own value.
struct NodePose {
  bool translated = false, rotated = false, scaled = false;
  glm::vec3 translation{0.0f}, scale{1.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
  std::vector<float> weights;  // morph target weights; empty: not animated
};

// The poses of `node_count` nodes at `time` seconds under the chosen animations (later
// channels on the same node and path win, as the specification leaves it to them).
std::vector<NodePose> pose_nodes(const std::vector<Animation>& animations, const std::vector<int>& playing,
                                 float time, std::size_t node_count);

// A channel's value at `time`: `width` floats (a rotation as x, y, z, w, normalised).
std::vector<float> sample_channel(const AnimationChannel& channel, float time);

}  // namespace tessera
