#include "renderer/camera/camera_coverage.h"

#include <algorithm>
#include <cmath>

#include "renderer/geometry/motion.h"

namespace tessera {
namespace {

// Rays from such a camera are finite everywhere on the film (what skipping them assumes).
bool well_formed(const RenderCamera& c) {
  const glm::mat3 m(c.camera_to_world);
  for (int i = 0; i < 4; ++i)
    if (!all_finite(c.camera_to_world[i])) return false;
  const float det = glm::determinant(m);
  const bool lens_ok = c.lens_radius <= 0.0f || (std::isfinite(c.lens_radius) && std::isfinite(c.focus_distance) &&
                                                 c.focus_distance > 0.0f);
  return lens_ok && std::isfinite(det) && det != 0.0f && std::isfinite(c.aspect) && c.aspect > 0.0f &&
         (c.projection == Camera::Projection::Perspective ? std::isfinite(c.tan_half_fov_y) && c.tan_half_fov_y > 0.0f
                                                          : std::isfinite(c.half_height) && c.half_height > 0.0f);
}

double distance_to_box(const glm::dvec3& p, const glm::dvec3& lo, const glm::dvec3& hi) {
  const glm::dvec3 d = glm::max(glm::max(lo - p, p - hi), glm::dvec3(0.0));
  return glm::length(d);
}

}  // namespace

// Where a camera moving by parts (renderer/geometry/motion.h) can be between two motion steps, seen
// from the halfway pose: its position within `drift` of it (the translation is linear), its
// orientation within `turn` radians (slerp turns about one axis, half the steps' angle either
// side). Only a rigid perspective camera without a lens qualifies (false: not bounded here).
bool CameraCoverage::moving_poses(const RenderCamera& camera, std::vector<Pose>& poses) {
  const std::vector<AffineParts>& steps = camera.motion.steps();
  if (camera.lens_radius > 0.0f || camera.projection != Camera::Projection::Perspective) return false;
  for (const AffineParts& p : steps) {
    const float off_diagonal = std::fabs(p.upper[1][0]) + std::fabs(p.upper[2][0]) + std::fabs(p.upper[2][1]);
    const float scale = std::fabs(p.upper[0][0] - 1.0f) + std::fabs(p.upper[1][1] - 1.0f) + std::fabs(p.upper[2][2] - 1.0f);
    if (!(off_diagonal + scale < 1e-5f)) return false;
  }
  for (std::size_t k = 0; k + 1 < steps.size(); ++k) {
    Pose pose{camera, 0.0, 0.0};
    pose.camera.motion = MotionTransform();
    pose.camera.camera_to_world = compose(interpolate(steps[k], steps[k + 1], 0.5f));
    const double cos_half = std::min(1.0, std::fabs(double(glm::dot(steps[k].rotation, steps[k + 1].rotation))));
    // Widened for float: the poses are made in float, each ray's direction normalised in float.
    pose.turn = std::acos(cos_half) * (1.0 + 1e-4) + 1e-5;
    pose.drift = 0.5 * glm::length(glm::dvec3(steps[k + 1].translation) - glm::dvec3(steps[k].translation)) * (1.0 + 1e-4) +
                 1e-5 * (1.0 + glm::length(glm::dvec3(steps[k].translation)));
    if (!well_formed(pose.camera) || !std::isfinite(pose.turn) || !std::isfinite(pose.drift)) return false;
    poses.push_back(pose);
  }
  return true;
}

CameraCoverage::CameraCoverage(const RenderCamera& camera, const SceneGeometry& geometry,
                               const CameraCoverageParams& params) {
  if (!well_formed(camera)) return;
  std::vector<Pose> poses;
  if (!camera.moves())
    poses.push_back({camera, 0.0, 0.0});
  else if (!moving_poses(camera, poses))
    return;
  all_ = false;
  x0_ = params.x0, y0_ = params.y0, width_ = params.width, height_ = params.height;
  covered_.assign(static_cast<std::size_t>(width_) * height_, 0);
  const std::vector<Bounds3> boxes = geometry.shutter_bounds();
  for (const Pose& pose : poses) {
    const glm::dmat4 world_to_camera = glm::inverse(glm::dmat4(pose.camera.camera_to_world));
    const View view = make_view(pose, params);
    for (const Bounds3& box : boxes) {
      cover_box(view, world_to_camera, box, params);
      if (all_) break;
    }
    if (all_) break;
  }
  if (all_) covered_.clear();
}

// The pose as the projection needs it.
CameraCoverage::View CameraCoverage::make_view(const Pose& pose, const CameraCoverageParams& params) {
  const RenderCamera& camera = pose.camera;
  View view;
  view.perspective = camera.projection == Camera::Projection::Perspective;
  view.sx = view.perspective ? double(camera.tan_half_fov_y) * camera.aspect : double(camera.half_height) * camera.aspect;
  view.sy = view.perspective ? double(camera.tan_half_fov_y) : double(camera.half_height);
  // A thin lens moves a ray's origin by up to its radius in the lens plane (z = 0) and aims it
  // at the pinhole ray's point on the focal plane (depth f), widened for the disk's rounding.
  view.lens = camera.lens_radius > 0.0f ? camera.lens_radius * (1.0 + 1e-4) : 0.0;
  view.focus = camera.focus_distance;
  view.drift = pose.drift, view.turn = pose.turn;
  view.eye = glm::dvec3(camera.camera_to_world[3]);
  const double kx = 1.0 + 2.0 * (params.filter_radius + 2.0) / params.full_width;
  const double ky = 1.0 + 2.0 * (params.filter_radius + 2.0) / params.full_height;
  view.cos_max = 1.0 / std::sqrt(1.0 + (kx * view.sx) * (kx * view.sx) + (ky * view.sy) * (ky * view.sy));
  view.cone = std::acos(view.cos_max);
  return view;
}

// A perspective ray meets a point at depth -z = |p| cos(angle to the axis); within the film
// (and a filter's reach beyond it) that angle is bounded, so the points of a box `distance`
// from the eye that rays can reach lie deeper than this (0: none is known). Through a lens a
// point at depth D < f is at most lens + D / cos_max from the camera, and one beyond f is
// deeper than f. From a position within drift of the eye, along an axis within turn of its
// axis, a ray reaches depth D >= (distance - drift) cos(cone + turn) - drift.
double CameraCoverage::cut_depth(const View& view, double distance) {
  if (view.moving()) {
    const double tilt = view.cone + view.turn;
    const double cut = tilt < kMaxAngle ? 0.5 * ((distance - view.drift) * std::cos(tilt) - view.drift) : 0.0;
    return cut > view.drift ? cut : 0.0;  // closer, the drift's angle is not bounded
  }
  const double cut = 0.5 * (distance - view.lens) * view.cos_max;
  return view.lens > 0.0 ? std::min(cut, 0.5 * view.focus) : cut;
}

// Covers the film pixels whose rays can reach `box`. A box within the camera's reach sets all_.
void CameraCoverage::cover_box(const View& view, const glm::dmat4& world_to_camera, const Bounds3& box,
                               const CameraCoverageParams& params) {
  if (box.empty()) return;
  // Widened for rounding: Embree's hits and generate_ray's directions are float.
  const double slack = 1e-5 * (glm::length(glm::dvec3(box.hi) - glm::dvec3(box.lo)) +
                               std::max(glm::length(glm::dvec3(box.lo)), glm::length(glm::dvec3(box.hi))));
  const glm::dvec3 lo = glm::dvec3(box.lo) - slack, hi = glm::dvec3(box.hi) + slack;
  glm::dvec3 corner[8];
  double deepest = -HUGE_VAL;
  for (int i = 0; i < 8; ++i) {
    corner[i] = glm::dvec3(world_to_camera * glm::dvec4(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z, 1.0));
    if (!std::isfinite(corner[i].x) || !std::isfinite(corner[i].y) || !std::isfinite(corner[i].z)) {
      all_ = true;
      return;
    }
    deepest = std::max(deepest, -corner[i].z);
  }
  // The box is cut at that depth and the rest projected; orthographic rays start on z = 0.
  const double cut = view.perspective ? cut_depth(view, distance_to_box(view.eye, lo, hi)) : 0.0;
  if (view.perspective && !(cut > 0.0)) {  // the camera (or its lens) is in or at the box
    all_ = true;
    return;
  }
  if (deepest < cut) return;  // all behind the camera
  // Through a lens or from a moving camera, the widening differs with depth: the box is covered
  // slab by slab, each with its own (depths doubling for a perspective camera, eight even
  // steps else).
  const int slabs = view.lens == 0.0 && !view.moving() ? 1
                    : view.perspective                    ? std::clamp(int(std::ceil(std::log2(deepest / cut))), 1, 24)
                                                          : 8;
  auto depth = [&](int k) {
    return k == slabs ? HUGE_VAL : view.perspective ? cut * std::exp2(k) : cut + (deepest - cut) * k / slabs;
  };
  for (int k = 0; k < slabs && !all_; ++k) {
    Rect r;
    if (slab_rect(corner, depth(k), depth(k + 1), view, params, r)) cover_rect(r, params);
  }
}

// The film rectangle (pixels) of the rays that can reach the box's part at depths [near, far]
// (false when there is none of it); a non-finite one sets all_.
bool CameraCoverage::slab_rect(const glm::dvec3 (&corner)[8], double near, double far, const View& view,
                               const CameraCoverageParams& params, Rect& rect) {
  double x_lo = HUGE_VAL, x_hi = -HUGE_VAL, y_lo = HUGE_VAL, y_hi = -HUGE_VAL, d_lo = HUGE_VAL, d_hi = -HUGE_VAL;
  auto project = [&](const glm::dvec3& p) {
    const double depth = view.perspective ? -p.z : 1.0;
    const double x = (p.x / (depth * view.sx) + 1.0) * 0.5 * params.full_width;
    const double y = (1.0 - p.y / (depth * view.sy)) * 0.5 * params.full_height;
    x_lo = std::min(x_lo, x), x_hi = std::max(x_hi, x), y_lo = std::min(y_lo, y), y_hi = std::max(y_hi, y);
    d_lo = std::min(d_lo, -p.z), d_hi = std::max(d_hi, -p.z);
  };
  auto inside = [&](const glm::dvec3& p) { return -p.z >= near && -p.z <= far; };
  for (int i = 0; i < 8; ++i) {
    if (inside(corner[i])) project(corner[i]);
    for (int axis = 1; axis < 8; axis <<= 1) {  // where the box's edges from this corner cross the slab's faces
      const int j = i | axis;
      if (j == i) continue;
      for (const double depth : {near, far}) {
        if ((-corner[i].z < depth) == (-corner[j].z < depth)) continue;
        const double t = (-depth - corner[i].z) / (corner[j].z - corner[i].z);
        project(corner[i] + t * (corner[j] - corner[i]));
      }
    }
  }
  if (x_lo > x_hi) return false;  // none of the box at these depths
  if (view.lens > 0.0) {
    // A ray through lens point l reaching depth D lands where the pinhole ray of a film point
    // l (1/D - 1/f) away (perspective, in units of the film plane at depth 1), or l (1 - D/f)
    // away (orthographic) would: the rectangle grows by the most of that over the slab's depths.
    auto spread = [&](double d) {
      return view.perspective ? std::fabs(1.0 / d - 1.0 / view.focus) : std::fabs(1.0 - d / view.focus);
    };
    const double reach = view.lens * std::max(spread(d_lo), spread(d_hi));
    const double grow_x = reach / view.sx * 0.5 * params.full_width, grow_y = reach / view.sy * 0.5 * params.full_height;
    x_lo -= grow_x, x_hi += grow_x, y_lo -= grow_y, y_hi += grow_y;
  }
  if (view.moving()) {
    // Seen from a position within drift of the eye, a point at depth D >= d_lo moves by at most
    // asin(drift / D); the camera turns by at most `turn`. Within the cone of film directions
    // widened by that angle delta, the film coordinate (tangent space) moves by at most
    // delta / cos^2 of the widened cone's half-angle.
    const double delta = view.turn + std::asin(std::min(1.0, view.drift / d_lo)), edge = view.cone + delta;
    if (!(edge < kMaxAngle)) {
      all_ = true;
      return false;
    }
    const double reach = delta / (std::cos(edge) * std::cos(edge));
    const double grow_x = reach / view.sx * 0.5 * params.full_width, grow_y = reach / view.sy * 0.5 * params.full_height;
    x_lo -= grow_x, x_hi += grow_x, y_lo -= grow_y, y_hi += grow_y;
  }
  if (!std::isfinite(x_lo) || !std::isfinite(x_hi) || !std::isfinite(y_lo) || !std::isfinite(y_hi)) {
    all_ = true;
    return false;
  }
  rect = {x_lo, x_hi, y_lo, y_hi};
  return true;
}

// Pixel f's samples land within filter_radius of its centre f + 0.5; kMargin more for the
// rounding of generate_ray's float directions (~1e-4 pixels; Embree's own rounding is in the
// boxes' slack).
void CameraCoverage::cover_rect(const Rect& r, const CameraCoverageParams& params) {
  const double reach = params.filter_radius + kMargin;
  auto first = [&](double lo, int begin, int size) {
    return static_cast<int>(std::clamp(std::ceil(lo - reach - 0.5), double(begin), double(begin + size)));
  };
  auto last = [&](double hi, int begin, int size) {
    return static_cast<int>(std::clamp(std::floor(hi + reach - 0.5), double(begin - 1), double(begin + size - 1)));
  };
  const int fx0 = first(r.x_lo, x0_, width_), fx1 = last(r.x_hi, x0_, width_);
  const int fy0 = first(r.y_lo, y0_, height_), fy1 = last(r.y_hi, y0_, height_);
  for (int y = fy0; y <= fy1; ++y)
    std::fill_n(covered_.begin() + static_cast<std::ptrdiff_t>(y - y0_) * width_ + (fx0 - x0_), std::max(0, fx1 - fx0 + 1),
                std::uint8_t{1});
}

std::uint64_t CameraCoverage::empty_pixels() const {
  if (all_) return 0;
  return static_cast<std::uint64_t>(std::count(covered_.begin(), covered_.end(), std::uint8_t{0}));
}

}  // namespace tessera
