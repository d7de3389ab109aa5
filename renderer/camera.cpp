#include "renderer/camera.h"

#include <algorithm>

#include <glm/gtc/matrix_transform.hpp>

namespace tessera {

Ray RenderCamera::generate_ray(const vec2& film, const vec2& lens, float time) const {
  // Screen point in camera space on the plane z = -1 (perspective) or z = 0 (orthographic);
  // `dir` stays unnormalised (its z is -1) until it is in world space: camera_to_world is
  // rigid, so one normalisation there serves both spaces.
  const vec2 ndc(2.0f * film.x - 1.0f, 1.0f - 2.0f * film.y);
  vec3 origin(0.0f), dir(0.0f, 0.0f, -1.0f);
  if (projection == Camera::Projection::Perspective)
    dir = vec3(ndc.x * tan_half_fov_y * aspect, ndc.y * tan_half_fov_y, -1.0f);
  else
    origin = vec3(ndc.x * half_height * aspect, ndc.y * half_height, 0.0f);
  if (lens_radius > 0.0f) {
    // Thin lens: every ray through the lens meets the pinhole ray on the focal plane.
    const vec3 focus = origin + dir * focus_distance;
    origin += vec3(lens_radius * sample_concentric_disk(lens), 0.0f);
    dir = focus - origin;
  }
  glm::mat4 moved;
  const glm::mat4* placed = &camera_to_world;
  if (!motion.empty()) placed = &(moved = motion.at(time));
  const glm::mat4& to_world = *placed;
  const vec3 world_dir = glm::mat3(to_world) * dir;
  const float length = glm::length(world_dir);
  Ray ray;
  // A pinhole's rays start at the camera's position: the transform's translation, exactly.
  ray.origin = origin == vec3(0.0f) ? vec3(to_world[3]) : vec3(to_world * vec4(origin, 1.0f));
  ray.direction = world_dir / length;
  // The near and far planes are depths along the view axis.
  const bool near = znear > 0.0f, far = zfar > znear && zfar > 0.0f;
  const float axial = near || far ? -dir.z / length : 1.0f;
  ray.tmin = near ? znear / axial : 0.0f;
  ray.tmax = far ? zfar / axial : std::numeric_limits<float>::infinity();
  ray.time = time;
  return ray;
}

glm::mat4 RenderCamera::world_to_camera(float time) const { return glm::inverse(camera_to_world_at(time)); }

glm::mat4 RenderCamera::world_to_ndc(float time) const {
  const float n = znear > 0.0f ? znear : 1e-3f;
  const float f = zfar > n ? zfar : 1e4f;
  glm::mat4 proj;
  if (projection == Camera::Projection::Perspective)
    proj = glm::perspectiveRH_NO(2.0f * std::atan(tan_half_fov_y), aspect, n, f);
  else
    proj = glm::orthoRH_NO(-half_height * aspect, half_height * aspect, -half_height,
                           half_height, n, f);
  return proj * world_to_camera(time);
}

RenderCamera make_camera(const Camera& cam, int width, int height, const CameraParams& params) {
  RenderCamera rc;
  rc.projection = cam.projection;
  rc.camera_to_world = cam.camera_to_world;
  if (std::any_of(cam.motion.begin(), cam.motion.end(), [&](const glm::mat4& m) { return m != cam.camera_to_world; })) {
    std::vector<glm::mat4> steps{cam.camera_to_world};
    steps.insert(steps.end(), cam.motion.begin(), cam.motion.end());
    rc.motion = MotionTransform(steps);
  }
  rc.aspect = static_cast<float>(width) / static_cast<float>(height);
  const float yfov = params.fov_degrees > 0.0f ? glm::radians(params.fov_degrees) : cam.yfov;
  rc.tan_half_fov_y = std::tan(0.5f * yfov);
  rc.half_height = cam.ymag;
  rc.znear = cam.znear;
  rc.zfar = cam.zfar;
  rc.lens_radius = 0.5f * params.aperture;
  rc.focus_distance = params.focus_distance > 0.0f ? params.focus_distance : 1.0f;
  return rc;
}

namespace {

// 36 mm film across the longer image side, 50 mm lens: tan of half the vertical field of view.
float film_tan_half_y(float aspect) { return aspect >= 1.0f ? 18.0f / (50.0f * aspect) : 18.0f / 50.0f; }

}  // namespace

Camera auto_camera(const Bounds3& bounds, int width, int height) {
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  const vec3 center = bounds.empty() ? vec3(0.0f) : bounds.center();
  const float radius = bounds.empty() ? 1.0f : std::max(0.5f * glm::length(bounds.diagonal()), 1e-6f);
  const float tan_half_y = film_tan_half_y(aspect);
  const float tan_half_min = std::min(tan_half_y, tan_half_y * aspect);
  Camera cam;
  cam.name = "automatic";
  cam.yfov = 2.0f * std::atan(tan_half_y);
  cam.camera_to_world = glm::translate(glm::mat4(1.0f), center + vec3(0, 0, radius / tan_half_min));
  return cam;
}

Camera look_at_camera(const vec3& eye, const vec3& target, const vec3& up, int width, int height) {
  Camera cam;
  cam.name = "look-at";
  cam.yfov = 2.0f * std::atan(film_tan_half_y(static_cast<float>(width) / static_cast<float>(height)));
  cam.camera_to_world = glm::inverse(glm::lookAt(eye, target, up));
  return cam;
}

float default_aspect(const Camera* cam) {
  if (!cam) return 16.0f / 9.0f;
  if (cam->projection == Camera::Projection::Orthographic) return cam->xmag / cam->ymag;
  return cam->aspect_ratio > 0.0f ? cam->aspect_ratio : 16.0f / 9.0f;
}

}  // namespace tessera
