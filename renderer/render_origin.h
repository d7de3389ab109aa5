// Where the renderer puts the world's origin. Floats resolve coordinates to 2^-24 of their
// size, so a small scene far from the origin is held coarsely however its rays are offset
// (the Cornell box 10,000 units out rendered 30% dark: its rays left surfaces 0.25 units off).
// A still scene that far for its size is rendered in a frame centred on it: its placements,
// cameras and lights are moved by -origin before anything is built, which keeps the
// precision its meshes have in their own frames; what leaves the renderer in world
// coordinates (the EXR's camera matrices, --pixel's positions) is moved back. An animated
// scene stays where it is (a frame is the same whether built alone or updated from the one
// before, so its frame cannot follow its motion), as does a scene near the origin (bit for
// bit what it was).
#pragma once

#include "renderer/math.h"
#include "renderer/scene/scene.h"

namespace tessera {

// The world point the render frame's origin sits at: the bounds' centre for a still scene
// that reaches farther from the origin than kFarForItsSize times its size, else 0.
constexpr float kFarForItsSize = 64.0f;
vec3 render_origin(const SceneDescription& scene);

// Moves the scene's placements, cameras, lights and bounds by -origin (0: nothing).
void move_to_render_frame(SceneDescription& scene, const vec3& origin);
Camera camera_in_render_frame(Camera camera, const vec3& origin);

}  // namespace tessera
