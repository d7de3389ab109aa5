// Turning a loaded scene and command-line choices into what render_frame needs; shared by
// the render and bench commands so both set scenes up the same way.
#pragma once

#include <memory>
#include <string>

#include "renderer/camera/camera.h"
#include "renderer/scene/render_scene.h"
#include "renderer/description/scene.h"

namespace tessera {

// The camera named or numbered by `choice` (empty: the scene's first camera, else an
// automatic one framing `framing`, or the scene's bounds when null). Throws UsageError for a
// camera the scene does not have.
Camera choose_camera(const SceneDescription& scene, const std::string& choice, int width, int height,
                     const Bounds3* framing = nullptr);

// Image size from the requested width/height (0 = not given) and the camera's aspect
// ratio; 960 pixels wide when neither is given.
void resolve_resolution(const Camera* camera, int& width, int& height);

// Triangles placed in the scene whose material emits light (counted per placement);
// `untextured_only` leaves out emission through an emissive texture.
std::uint64_t emissive_triangle_count(const SceneDescription& scene, bool untextured_only = false);

// Distance along the view axis to what the centre of the image sees, for autofocus.
float autofocus_distance(const RenderScene& scene, const RenderCamera& camera);

// A scene set up the way bench and scaling measure it: the file's first camera (else an
// automatic one), the 'auto' background or the environment image `envmap` when given,
// `width` pixels wide, height from the camera.
struct MeasuredScene {
  std::unique_ptr<RenderScene> scene;
  RenderCamera camera;
  int width = 0, height = 0;
  double load_seconds = 0.0;  // reading, decoding and converting the file
  double build_seconds = 0.0;  // the RenderScene: BVH, textures, lights
};
MeasuredScene load_measured_scene(const std::string& path, int width, const std::string& envmap = "");

}  // namespace tessera
