// Where the renderer puts the world's origin. Floats resolve coordinates to 2^-24 of their
// size, so a small scene far from the origin is held coarsely however its rays are offset
// (the Cornell box 10,000 units out rendered 30% dark: its rays left surfaces 0.25 units off).
// A scene that far for its size is rendered in a frame centred on it: its placements,
// cameras and lights are moved by -origin before anything is built, which keeps the
// precision its meshes have in their own frames; what leaves the renderer in world
// coordinates (the EXR's camera matrices, --pixel's positions) is moved back. A scene near
// the origin stays where it is (bit for bit what it was).
// A frame of an animation is the same whether built alone or updated from the frame before
// (RenderScene::update): its origin is a function of its own bounds, and an update to a frame
// whose origin differs builds anew. So that a moving scene keeps its origin over many frames,
// an animated scene's origin is its centre rounded to a grid of cells at least kAnimatedCell
// times its size (a power of two), which leaves it within 8 times its size of it on each axis.
#pragma once

#include "renderer/util/math.h"
#include "renderer/description/scene.h"

namespace tessera {

// The world point the render frame's origin sits at: for a scene that reaches farther from the
// origin than kFarForItsSize times its size, the bounds' centre (an animated scene's rounded
// to its grid), else 0.
constexpr float kFarForItsSize = 64.0f;
constexpr float kAnimatedCell = 8.0f;
vec3 render_origin(const SceneDescription& scene);

// Moves the scene's placements, cameras, lights and bounds by -origin (0: nothing).
void move_to_render_frame(SceneDescription& scene, const vec3& origin);
Camera camera_in_render_frame(Camera camera, const vec3& origin);

}  // namespace tessera
