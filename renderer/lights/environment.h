// What a ray that leaves the scene sees: a uniform background radiance, or an
// equirectangular environment image (decoded by imageio: .hdr and .exr above all).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "renderer/sampling/distribution.h"
#include "renderer/util/float_image.h"
#include "renderer/util/math.h"

namespace tessera {

struct EnvironmentParams {
  vec3 background{0.0f};  // radiance of a uniform background (used when no image)
  std::string image_path;  // the file `image` was read from (imageio's read_environment_image)
  std::shared_ptr<const FloatImage> image;  // equirectangular image; null = none
  float scale = 1.0f;  // radiance multiplier for the image
  float rotate_degrees = 0.0f;  // rotation about +Y
};

class Environment {
 public:
  explicit Environment(const EnvironmentParams& params);

  vec3 radiance(const vec3& direction) const;
  bool has_image() const { return width_ > 0; }

  // Importance sampling of the image: a direction in proportion to radiance x sin(theta)
  // (a 2D piecewise-constant distribution over the equirectangular texels), its
  // solid-angle pdf, and the pdf of any direction. Only when has_image().
  vec3 sample(const vec2& u, float& pdf) const;
  float pdf(const vec3& direction) const;
  vec3 uv_to_direction(const vec2& uv) const;

  // Image coordinates in [0,1]^2 (u right, v down) of a world direction: the centre of the
  // image faces +X, u grows towards +Z (u = 0.75 looks along +Z), the top row is +Y.
  // This is Blender's equirectangular mapping after its glTF axis conversion (Blender
  // u = 0.5 - atan2(y_b, x_b) / 2 pi with y_b = -z), so one file lights both the same way.
  vec2 direction_to_uv(const vec3& direction) const;

 private:
  vec3 background_;
  float scale_;
  float cos_rot_ = 1.0f, sin_rot_ = 0.0f;
  int width_ = 0, height_ = 0;
  std::vector<vec3> texels_;  // linear RGB, top row first
  Distribution1D rows_;  // marginal over rows
  std::vector<Distribution1D> columns_;  // conditional over columns, per row

  void build_distribution();
};

}  // namespace tessera
