// The render camera: a glTF perspective or orthographic camera (or an automatic one that
// frames the scene), with an optional thin lens for depth of field, moving or not while the
// shutter is open.
#pragma once

#include "renderer/geometry/motion.h"
#include "renderer/util/ray.h"
#include "renderer/description/scene.h"

namespace tessera {

struct CameraParams {
  float fov_degrees = 0.0f;  // > 0 overrides a perspective camera's vertical field of view
  float aperture = 0.0f;  // lens diameter in scene units; 0 = pinhole
  float focus_distance = 0.0f;  // 0 = chosen by the caller (see render.cpp)
};

struct RenderCamera {
  Camera::Projection projection = Camera::Projection::Perspective;
  glm::mat4 camera_to_world{1.0f};  // at the shutter's opening
  // A camera that moves while the shutter is open: its camera_to_world at each motion step,
  // position linear and rotation by slerp in between. Empty: it stands still.
  MotionTransform motion;
  float tan_half_fov_y = 0.0f;  // perspective
  float half_height = 1.0f;  // orthographic: ymag
  float aspect = 1.0f;  // image width / height
  float lens_radius = 0.0f, focus_distance = 1.0f;
  float znear = 0.0f, zfar = 0.0f;
  // The world point at the origin of the frame its rays are in (RenderScene::origin): its
  // projections below are of world coordinates.
  vec3 origin{0.0f};

  // film: position on the image in [0,1]^2, (0,0) the top-left corner; lens in [0,1)^2;
  // time: the fraction of the shutter in [0, 1), which the ray carries.
  Ray generate_ray(const vec2& film, const vec2& lens, float time = 0.0f) const;
  // generate_ray for n points at once (lens[k] and time[k] as there): the same rays bit for
  // bit. A still pinhole's, nearly every render's, are computed four at a time (SSE).
  void generate_rays(const vec2* film, const vec2* lens, const float* time, int n, Ray* out) const;
  bool moves() const { return !motion.empty(); }
  glm::mat4 camera_to_world_at(float time) const { return motion.empty() ? camera_to_world : motion.at(time); }
  // Where the camera looks and stands: at the shutter's opening.
  vec3 forward() const { return -glm::vec3(camera_to_world[2]); }
  vec3 position() const { return glm::vec3(camera_to_world[3]); }
  // Its projections of world coordinates at `time`, the fraction of the shutter (0: the opening).
  glm::mat4 world_to_camera(float time = 0.0f) const;
  glm::mat4 world_to_ndc(float time = 0.0f) const;  // camera space -> [-1,1]^2 screen, z = depth
};

// The camera from the scene description (vertical fov, aspect from the image), with its
// motion when it has any (Camera::motion; steps equal to step 0 are no motion). In world
// coordinates: for a RenderScene, RenderScene::camera makes it for the scene's render frame.
RenderCamera make_camera(const Camera& cam, int width, int height, const CameraParams& params);

// A perspective camera on +Z of the bounds' centre looking down -Z that frames the bounding
// sphere (a 50 mm lens on a 36 mm film, as the Cycles comparison script sets up).
Camera auto_camera(const Bounds3& bounds, int width, int height);

// A perspective camera with the automatic camera's lens that circles the bounds' centre: at
// `azimuth_degrees` about +Y from +Z (towards +X) and `elevation_degrees` above the XZ plane,
// looking at the centre with +Y up, `distance` away (0: the automatic camera's, which frames
// the bounding sphere). Azimuth and elevation 0 is the automatic camera's place. The caller
// keeps the elevation strictly between -90 and 90.
Camera orbit_camera(const Bounds3& bounds, float azimuth_degrees, float elevation_degrees, float distance, int width,
                    int height);

// A perspective camera at `eye` looking at `target` with `up` upwards in the image, with the
// automatic camera's lens (50 mm on 36 mm film across the longer side). The caller checks
// that eye != target and that up is not along the view.
Camera look_at_camera(const vec3& eye, const vec3& target, const vec3& up, int width, int height);

// Width / height of the image for a camera: the camera's aspect ratio, else 16:9.
float default_aspect(const Camera* cam);

}  // namespace tessera
