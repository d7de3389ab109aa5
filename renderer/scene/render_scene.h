// Everything the integrator reads while rendering, built once from a SceneDescription:
// the Embree BVH, materials with decoded textures, lights and the environment.
#pragma once

#include <embree3/rtcore.h>

#include <algorithm>
#include <memory>

#include "renderer/camera/camera.h"
#include "renderer/lights/environment.h"
#include "renderer/lights/light_tree.h"
#include "renderer/lights/area_lights.h"
#include "renderer/materials/materials.h"
#include "renderer/geometry/motion.h"
#include "renderer/description/scene.h"
#include "renderer/geometry/scene_geometry.h"

namespace tessera {

// Owns the Embree device; errors Embree reports become exceptions at the next check.
class EmbreeDevice {
 public:
  EmbreeDevice();
  ~EmbreeDevice();
  EmbreeDevice(const EmbreeDevice&) = delete;
  EmbreeDevice& operator=(const EmbreeDevice&) = delete;
  RTCDevice get() const { return device_; }

 private:
  RTCDevice device_;
};

struct RenderScene {
  // Takes the description by value: the BVH and shading keep pointers into it. It is kept
  // moved to the render frame (render_origin.h).
  RenderScene(SceneDescription scene, const EnvironmentParams& env);

  // The world point at the render frame's origin: 0 unless the scene is far from the origin
  // for its size (render_origin.h).
  vec3 origin{0.0f};
  // A camera of the world (the description's as loaded, the command line's, the automatic
  // one), looking at this scene in its render frame.
  RenderCamera camera(const Camera& cam, int width, int height, const CameraParams& params) const;
  // Throws std::invalid_argument unless `camera` looks at this scene's render frame (made by
  // camera(), or by make_camera for a scene that was not moved).
  void check_camera(const RenderCamera& camera) const;

  SceneDescription description;
  EmbreeDevice device;
  Environment environment;
  MaterialTable materials;
  std::unique_ptr<SceneGeometry> geometry;
  std::unique_ptr<AreaLights> area_lights;  // emissive triangles
  // Per punctual light (description.lights): its transform over the shutter when it moves,
  // decomposed once; empty when it stands still.
  std::vector<MotionTransform> light_motion;
  LightTree light_tree;  // over the point and spot lights, for many-light sampling
  double bvh_build_seconds = 0.0;

  // Something moves or deforms while the shutter is open (the camera aside).
  bool moves() const {
    return geometry->moves() ||
           std::any_of(light_motion.begin(), light_motion.end(), [](const MotionTransform& m) { return !m.empty(); });
  }

  // Makes this the scene `next` describes, when next is another frame of the same file and
  // variant (the same materials and images, which are not compared) with the structure built
  // here (SceneGeometry::can_update) and the same render origin: the vertex arrays,
  // placements, cameras and lights that differ are taken from next, their BVHs rebuilt and
  // the area lights found again, while the textures, the environment and the BVHs of whatever
  // did not change are kept. False, and next untouched, otherwise: then build a new
  // RenderScene.
  bool update(SceneDescription& next);
  std::uint64_t rebuilt_triangles = 0;  // by the last update
};

}  // namespace tessera
