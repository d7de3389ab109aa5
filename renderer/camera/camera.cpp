#include "renderer/camera/camera.h"

#include <algorithm>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

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

namespace {

// Four rays of a still perspective pinhole, generate_ray's arithmetic lane by lane (the same
// operations in the same order, IEEE-exact in SSE as in scalar code: the same bits).
#if defined(__SSE2__)
void pinhole_rays4(const RenderCamera& c, const vec2* film, const float* time, Ray* out) {
  const auto lane = [&](auto field) { return _mm_setr_ps(field(0), field(1), field(2), field(3)); };
  const __m128 one = _mm_set1_ps(1.0f), two = _mm_set1_ps(2.0f);
  const __m128 ndc_x = _mm_sub_ps(_mm_mul_ps(two, lane([&](int k) { return film[k].x; })), one);
  const __m128 ndc_y = _mm_sub_ps(one, _mm_mul_ps(two, lane([&](int k) { return film[k].y; })));
  const __m128 tan_y = _mm_set1_ps(c.tan_half_fov_y);
  const __m128 dx = _mm_mul_ps(_mm_mul_ps(ndc_x, tan_y), _mm_set1_ps(c.aspect));
  const __m128 dy = _mm_mul_ps(ndc_y, tan_y);
  const __m128 dz = _mm_set1_ps(-1.0f);
  const glm::mat4& m = c.camera_to_world;
  __m128 w[3];
  for (int r = 0; r < 3; ++r)  // glm's mat3 * vec3: m[0][r] x + m[1][r] y + m[2][r] z
    w[r] = _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_set1_ps(m[0][r]), dx), _mm_mul_ps(_mm_set1_ps(m[1][r]), dy)),
                      _mm_mul_ps(_mm_set1_ps(m[2][r]), dz));
  const __m128 length = _mm_sqrt_ps(_mm_add_ps(_mm_add_ps(_mm_mul_ps(w[0], w[0]), _mm_mul_ps(w[1], w[1])), _mm_mul_ps(w[2], w[2])));
  alignas(16) float d[3][4], len[4];
  for (int r = 0; r < 3; ++r) _mm_store_ps(d[r], _mm_div_ps(w[r], length));
  _mm_store_ps(len, length);
  const bool near = c.znear > 0.0f, far = c.zfar > c.znear && c.zfar > 0.0f;
  for (int k = 0; k < 4; ++k) {
    Ray& ray = out[k];
    ray.origin = vec3(m[3]);
    ray.direction = vec3(d[0][k], d[1][k], d[2][k]);
    const float axial = near || far ? 1.0f / len[k] : 1.0f;  // generate_ray's -dir.z / length, dir.z = -1
    ray.tmin = near ? c.znear / axial : 0.0f;
    ray.tmax = far ? c.zfar / axial : std::numeric_limits<float>::infinity();
    ray.time = time[k];
  }
}
#endif

}  // namespace

void RenderCamera::generate_rays(const vec2* film, const vec2* lens, const float* time, int n, Ray* out) const {
  int k = 0;
#if defined(__SSE2__)
  if (projection == Camera::Projection::Perspective && lens_radius <= 0.0f && motion.empty())
    for (; k + 4 <= n; k += 4) pinhole_rays4(*this, film + k, time + k, out + k);
#endif
  for (; k < n; ++k) out[k] = generate_ray(film[k], lens[k], time[k]);
}

glm::mat4 RenderCamera::world_to_camera(float time) const {
  glm::mat4 to_world = camera_to_world_at(time);
  to_world[3] += glm::vec4(origin, 0.0f);
  return glm::inverse(to_world);
}

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

namespace {

// How far from the bounds' centre the automatic lens sees the whole bounding sphere.
float framing_distance(const Bounds3& bounds, int width, int height) {
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  const float radius = bounds.empty() ? 1.0f : std::max(0.5f * glm::length(bounds.diagonal()), 1e-6f);
  const float tan_half_y = film_tan_half_y(aspect);
  return radius / std::min(tan_half_y, tan_half_y * aspect);
}

}  // namespace

Camera auto_camera(const Bounds3& bounds, int width, int height) {
  const vec3 center = bounds.empty() ? vec3(0.0f) : bounds.center();
  Camera cam;
  cam.name = "automatic";
  cam.yfov = 2.0f * std::atan(film_tan_half_y(static_cast<float>(width) / static_cast<float>(height)));
  cam.camera_to_world = glm::translate(glm::mat4(1.0f), center + vec3(0, 0, framing_distance(bounds, width, height)));
  return cam;
}

Camera orbit_camera(const Bounds3& bounds, float azimuth_degrees, float elevation_degrees, float distance, int width,
                    int height) {
  const vec3 center = bounds.empty() ? vec3(0.0f) : bounds.center();
  const float azimuth = glm::radians(azimuth_degrees), elevation = glm::radians(elevation_degrees);
  const vec3 direction(std::cos(elevation) * std::sin(azimuth), std::sin(elevation), std::cos(elevation) * std::cos(azimuth));
  const float d = distance > 0.0f ? distance : framing_distance(bounds, width, height);
  Camera cam = look_at_camera(center + d * direction, center, vec3(0.0f, 1.0f, 0.0f), width, height);
  cam.name = "orbit";
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
