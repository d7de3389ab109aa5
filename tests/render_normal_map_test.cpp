// Normal maps in tangent space, on a mesh without TANGENT (the frame comes from its UVs):
// a flat floor whose normal map tilts the normal by 30 degrees towards +x of the texture
// (or towards the top of the image), under a directional light tilted the same way, is lit
// head-on (cos = 1); a mirrored tangent frame would give cos 60 degrees = 0.5.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "renderer/render/render.h"
#include "tests/scene_builders.h"

namespace tessera {
namespace {

double lit_floor(vec3 map_normal, vec3 light_towards) {
  SceneDescription s;
  Image img;
  img.width = img.height = 1;
  img.channels = 3;
  img.bits_per_channel = 32;
  const vec3 texel = map_normal * 0.5f + 0.5f;  // [-1,1] -> [0,1], stored as float
  std::vector<std::uint8_t> bytes(3 * sizeof(float));
  std::memcpy(bytes.data(), &texel[0], 3 * sizeof(float));
  img.pixels = std::make_shared<const std::vector<std::uint8_t>>(std::move(bytes));
  s.images.push_back(img);
  Material m = test::diffuse(vec3(0.5f));
  m.normal_texture.image = 0;
  // Floor in the xz plane facing +y; texture u along +x, the image's top towards -z.
  test::add_mesh(s, test::make_quad({0, 0, 0}, {10, 0, 0}, {0, 0, -10}, test::add_material(s, m)));
  PunctualLight sun;
  sun.type = PunctualLight::Type::Directional;
  sun.direction = -glm::normalize(light_towards);
  sun.intensity = 1.0f;
  s.lights.push_back(sun);
  RenderSettings st;
  st.width = st.height = 2;
  st.spp = 1;
  st.max_bounces = 1;
  RenderScene rs(std::move(s), EnvironmentParams{});
  const FrameImage f = render_frame(rs, make_camera(test::look_at({0, 2, 1}, {0, 0, 0}, 1.0f), 2, 2, {}), st).image;
  return f.rgb[0] / (0.5 / M_PI);  // the cosine the shading saw
}

TEST(RenderNormalMap, TiltsTowardsTextureUAndImageUp) {
  const float s = std::sin(glm::radians(30.0f)), c = std::cos(glm::radians(30.0f));
  // +x in the map = +u = world +x.
  EXPECT_NEAR(lit_floor({s, 0, c}, {s, c, 0}), 1.0, 1e-4);
  EXPECT_NEAR(lit_floor({s, 0, c}, {-s, c, 0}), 0.5, 1e-4);
  // +y in the map = up the image = world -z here.
  EXPECT_NEAR(lit_floor({0, s, c}, {0, c, -s}), 1.0, 1e-4);
  EXPECT_NEAR(lit_floor({0, s, c}, {0, c, s}), 0.5, 1e-4);
  EXPECT_NEAR(lit_floor({0, 0, 1}, {0, 1, 0}), 1.0, 1e-4);  // the flat map changes nothing
}

}  // namespace
}  // namespace tessera
