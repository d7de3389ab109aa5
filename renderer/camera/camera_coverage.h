// Which pixels' camera rays can hit anything at all. Each triangle list's world box over the
// shutter (SceneGeometry::shutter_bounds: everywhere it can be while the shutter is open),
// projected through a still pinhole (or orthographic) camera, covers every film point whose
// ray could reach it; a pixel whose filter footprint (and a twentieth of a pixel) meets none
// of those rectangles sees only the background, so its camera rays need no traversal: the
// answer is known (the image is the same bit for bit, tests/camera_coverage_test.cpp). A
// product shot on an empty background spends most of its camera samples there: 86% of
// MetalRoughSpheres'. A thin lens widens each rectangle by how far its rays stray from the
// pinhole's at the box's depths; a moving (rigid, perspective, pinhole) camera widens them by
// how far it can drift and turn from each pair of motion steps' halfway pose. Conservative by
// construction: a box within a small distance of the camera or its lens, a moving camera with
// a lens, an orthographic or a scaled one, a non-finite camera: every pixel may hit.
#pragma once

#include <cstdint>
#include <vector>

#include "renderer/camera/camera.h"
#include "renderer/geometry/scene_geometry.h"

namespace tessera {

struct CameraCoverageParams {
  int full_width = 0, full_height = 0;  // the frame's pixels (a crop's frame, not the crop)
  int x0 = 0, y0 = 0, width = 0, height = 0;  // the pixels that will be asked about
  float filter_radius = 0.5f;  // how far from a pixel's centre its samples can land, in pixels
};

class CameraCoverage {
 public:
  CameraCoverage() = default;  // every pixel may hit
  // The coverage of the scene's triangles over the shutter; every pixel may hit when the
  // camera's rays may not be finite or its motion is not one bounded here.
  CameraCoverage(const RenderCamera& camera, const SceneGeometry& geometry, const CameraCoverageParams& params);
  // Whether a camera ray of a sample of frame pixel (fx, fy) may hit a triangle.
  bool may_hit(int fx, int fy) const {
    if (all_) return true;
    const int x = fx - x0_, y = fy - y0_;
    if (x < 0 || y < 0 || x >= width_ || y >= height_) return true;
    return covered_[static_cast<std::size_t>(y) * width_ + x] != 0;
  }
  // The pixels asked about that cannot hit anything.
  std::uint64_t empty_pixels() const;

 private:
  struct Rect {
    double x_lo, x_hi, y_lo, y_hi;  // film pixels
  };
  struct Pose {  // a still camera, or a moving one's halfway pose between two motion steps
    RenderCamera camera;
    double drift = 0, turn = 0;  // how far from it the camera can be (scene units, radians)
  };
  struct View {  // the camera as the projection needs it (camera space, depth D = -z)
    bool perspective = true;
    double sx = 1, sy = 1;  // film half-extent: tangents (perspective) or scene units
    double lens = 0, focus = 1;  // thin lens radius (0: pinhole) and focus distance
    double drift = 0, turn = 0;  // a moving camera's Pose
    glm::dvec3 eye{0.0};  // the camera's position (world)
    double cos_max = 1, cone = 0;  // perspective: the film's (and filter reach's) half-angle from the axis
    bool moving() const { return drift > 0 || turn > 0; }
  };
  static constexpr double kMargin = 0.05;  // pixels
  static constexpr double kMaxAngle = 1.5;  // radians from the axis: beyond, nothing is bounded
  static bool moving_poses(const RenderCamera& camera, std::vector<Pose>& poses);
  static View make_view(const Pose& pose, const CameraCoverageParams& params);
  static double cut_depth(const View& view, double distance);
  void cover_box(const View& view, const glm::dmat4& world_to_camera, const Bounds3& box,
                 const CameraCoverageParams& params);
  bool slab_rect(const glm::dvec3 (&corner)[8], double near, double far, const View& view,
                 const CameraCoverageParams& params, Rect& rect);
  void cover_rect(const Rect& r, const CameraCoverageParams& params);

  bool all_ = true;
  int x0_ = 0, y0_ = 0, width_ = 0, height_ = 0;
  std::vector<std::uint8_t> covered_;
};

}  // namespace tessera
