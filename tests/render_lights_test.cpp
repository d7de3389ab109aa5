// Closed forms for each kind of light, rendered: a Lambertian floor (albedo a) under a
// point light of I candela shows a/pi * I * cos(theta) / d^2; under a directional light of
// E lux, a/pi * E * cos(theta); a spot light falls off as KHR_lights_punctual specifies.
// And a slab of absorbing glass transmits exp(-sigma t) times the Fresnel terms.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <tuple>

#include "renderer/render/render.h"
#include "tests/scene_builders.h"

namespace tessera {
namespace {

constexpr float kAlbedo = 0.6f;

SceneDescription floor_scene() {
  SceneDescription s;
  test::add_mesh(s, test::make_quad({0, 0, 0}, {100, 0, 0}, {0, 0, -100}, test::add_material(s, test::diffuse(vec3(kAlbedo)))));
  return s;
}

// Mean red value of a tiny image whose pixels all look at `target` on the floor.
double floor_radiance(SceneDescription scene, vec3 target, int spp = 4) {
  RenderSettings st;
  st.width = st.height = 4;
  st.spp = spp;
  st.max_bounces = 1;
  RenderScene rs(std::move(scene), EnvironmentParams{});
  const Camera cam = test::look_at(target + vec3(0.0f, 1.0f, 0.3f), target, 0.01f);
  const FrameImage img = render_frame(rs, make_camera(cam, st.width, st.height, {}), st).image;
  double sum = 0.0;
  for (std::size_t i = 0; i < img.rgb.size(); i += 3) sum += img.rgb[i];
  return sum / (st.width * st.height);
}

TEST(RenderLights, PointLightOverADiffusePlane) {
  for (vec3 target : {vec3(0.0f), vec3(0.8f, 0.0f, -0.3f), vec3(-2.0f, 0.0f, 1.0f)}) {
    SceneDescription s = floor_scene();
    PunctualLight l;
    l.type = PunctualLight::Type::Point;
    l.position = {0.0f, 1.5f, 0.0f};
    l.intensity = 7.0f;
    l.color = vec3(1.0f, 0.5f, 0.25f);
    s.lights.push_back(l);
    const vec3 to_light = l.position - target;
    const double d2 = glm::dot(to_light, to_light), cos_theta = to_light.y / std::sqrt(d2);
    const double expected = kAlbedo / M_PI * l.intensity * cos_theta / d2;
    EXPECT_NEAR(floor_radiance(s, target), expected, 2e-3 * expected) << target.x << "," << target.z;
  }
}

TEST(RenderLights, DirectionalLightOverADiffusePlane) {
  for (float angle : {0.0f, 30.0f, 75.0f}) {
    SceneDescription s = floor_scene();
    PunctualLight l;
    l.type = PunctualLight::Type::Directional;
    l.intensity = 3.0f;  // lux
    const float a = glm::radians(angle);
    l.direction = {std::sin(a), -std::cos(a), 0.0f};  // shining down, tilted
    s.lights.push_back(l);
    const double expected = kAlbedo / M_PI * l.intensity * std::cos(a);
    EXPECT_NEAR(floor_radiance(s, vec3(0.0f)), expected, 2e-3 * expected) << angle;
  }
}

// KHR_lights_punctual's recommended spot falloff: with cos(angle to the axis) = c,
// t = clamp((c - cos(outer)) / (cos(inner) - cos(outer)), 0, 1), intensity scaled by t^2.
TEST(RenderLights, SpotLightFallsOffAsSpecified) {
  const float inner = glm::radians(15.0f), outer = glm::radians(35.0f), h = 2.0f;
  for (float degrees : {5.0f, 20.0f, 25.0f, 30.0f, 40.0f}) {
    SceneDescription s = floor_scene();
    PunctualLight l;
    l.type = PunctualLight::Type::Spot;
    l.position = {0.0f, h, 0.0f};
    l.direction = {0.0f, -1.0f, 0.0f};
    l.intensity = 10.0f;
    l.inner_cone_angle = inner;
    l.outer_cone_angle = outer;
    s.lights.push_back(l);
    const float a = glm::radians(degrees);
    const vec3 target(h * std::tan(a), 0.0f, 0.0f);
    const double c = std::cos(a), d2 = h * h + target.x * target.x;
    const double t = std::clamp((c - std::cos(outer)) / (std::cos(inner) - std::cos(outer)), 0.0, 1.0);
    const double expected = kAlbedo / M_PI * l.intensity * t * t * c / d2;
    EXPECT_NEAR(floor_radiance(s, target), expected, 2e-3 * expected + 1e-7) << degrees << " degrees";
  }
}

// A box of glass (ior 1.5, smooth, thickness t, KHR_materials_volume attenuation) in front
// of an emitter of radiance 1, seen head-on: each face transmits 1 - R (R = 0.04 at normal
// incidence), the volume exp(-sigma t), and light bouncing between the faces adds a
// geometric series: T = (1 - R)^2 e^(-sigma t) / (1 - R^2 e^(-2 sigma t)).
TEST(RenderLights, AbsorbingGlassSlabTransmitsBeerLambertTimesFresnel) {
  const float t = 1.0f, distance = 2.0f;
  const vec3 color(0.8f, 0.5f, 0.2f);  // transmitted fraction after `distance`
  SceneDescription s;
  Material glass;
  glass.base_color_factor = vec4(1.0f);
  glass.metallic_factor = 0.0f;
  glass.roughness_factor = 0.0f;
  glass.transmission_factor = 1.0f;
  glass.thickness_factor = t;
  glass.attenuation_color = color;
  glass.attenuation_distance = distance;
  const int g = test::add_material(s, glass);
  const float h = 3.0f, z = t / 2;  // the slab spans z in [-t/2, t/2]
  for (const auto& [c, u, v] : {std::tuple{vec3(0, 0, z), vec3(h, 0, 0), vec3(0, h, 0)},
                                 {vec3(0, 0, -z), vec3(0, h, 0), vec3(h, 0, 0)},
                                 {vec3(h, 0, 0), vec3(0, 0, z), vec3(0, h, 0)},
                                 {vec3(-h, 0, 0), vec3(0, h, 0), vec3(0, 0, z)},
                                 {vec3(0, h, 0), vec3(0, 0, z), vec3(h, 0, 0)},
                                 {vec3(0, -h, 0), vec3(h, 0, 0), vec3(0, 0, z)}})
    test::add_mesh(s, test::make_quad(c, u, v, g));  // six faces, all facing outwards
  test::add_mesh(s, test::make_quad({0, 0, -2}, {10, 0, 0}, {0, 10, 0}, test::add_material(s, test::emitter(vec3(1.0f)))));
  RenderSettings st;
  st.width = st.height = 16;
  st.spp = 64;
  st.max_bounces = 32;
  RenderScene rs(std::move(s), EnvironmentParams{});
  const FrameImage img = render_frame(rs, make_camera(test::look_at({0, 0, 4}, {0, 0, 0}, 5.0f), 16, 16, {}), st).image;
  const double r = 0.04;
  for (int k = 0; k < 3; ++k) {
    const double absorbed = std::pow(color[k], t / distance);  // e^(-sigma t), sigma = -ln(color) / distance
    const double expected = (1 - r) * (1 - r) * absorbed / (1 - r * r * absorbed * absorbed);
    double mean = 0.0;
    for (std::size_t i = k; i < img.rgb.size(); i += 3) mean += img.rgb[i];
    mean /= st.width * st.height;
    EXPECT_NEAR(mean, expected, 0.01 * expected) << "channel " << k;
  }
}

}  // namespace
}  // namespace tessera
