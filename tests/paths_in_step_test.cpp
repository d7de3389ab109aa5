// trace_paths_from, the paths of a sample group traced in step, against trace_path_from for
// each path alone (a second method): the same radiance and first-hit features bit for bit and
// the same counters, on scenes whose paths end in every way (emitters and area lights, thin and
// volume transmission, dispersion drawing wavelengths, textures, an environment image) and
// with groups of every size up to a packet.
#include <gtest/gtest.h>

#include <random>

#include "renderer/integrator/path_tracer.h"
#include "scene_io/gltf_loader.h"
#include "tests/test_support.h"
#include "imageio/environment_image.h"

namespace tessera {
namespace {

void expect_paths_alike(const std::string& scene_file, const EnvironmentParams& env) {
  const RenderScene rs(load_gltf(test::scene_path(scene_file)).scene, env);
  // From the file's camera, else from outside a corner of the bounds, towards their centre.
  const Bounds3& b = rs.description.bounds;
  const vec3 centre = 0.5f * (b.lo + b.hi);
  const vec3 eye = rs.description.cameras.empty() ? centre + 1.5f * (b.hi - centre)
                                                  : vec3(rs.description.cameras[0].camera_to_world[3]);
  std::mt19937 gen(5);
  std::normal_distribution<float> n01;
  constexpr int kMost = SceneGeometry::kPacketSize;
  for (int group = 0; group < 40; ++group) {
    const int n = 1 + group % kMost;
    Ray rays[kMost];
    ClosestHit known[kMost];
    std::vector<Sampler> alone, stepped;
    for (int k = 0; k < n; ++k) {
      const vec3 to = centre + 0.4f * glm::length(b.hi - centre) * vec3(n01(gen), n01(gen), n01(gen));
      rays[k] = Ray{eye, glm::normalize(to - eye), 0.0f, std::numeric_limits<float>::infinity(), 0.0f};
      known[k].found = rs.geometry->intersect(rays[k], known[k].hit);
      alone.emplace_back(SamplerKind::sobol, 3, group, static_cast<std::uint32_t>(k), 1);
    }
    stepped = alone;
    Sampler* rngs[kMost];
    for (int k = 0; k < n; ++k) rngs[k] = &stepped[k];
    FirstHit firsts[kMost];
    vec3 radiance[kMost];
    PathCounters in_step, one_by_one;
    trace_paths_from(rs, {}, n, rays, known, rngs, firsts, in_step, radiance);
    for (int k = 0; k < n; ++k) {
      FirstHit first;
      const vec3 r = trace_path_from(rs, {}, rays[k], &known[k], alone[k], first, one_by_one);
      for (int c = 0; c < 3; ++c) {
        ASSERT_TRUE(same_bits(radiance[k][c], r[c])) << scene_file << " group " << group << " path " << k;
        ASSERT_TRUE(same_bits(firsts[k].albedo[c], first.albedo[c])) << scene_file << " group " << group << " path " << k;
        ASSERT_TRUE(same_bits(firsts[k].normal[c], first.normal[c])) << scene_file << " group " << group << " path " << k;
      }
      ASSERT_EQ(firsts[k].hit, first.hit);
      ASSERT_TRUE(same_bits(firsts[k].distance, first.distance));
    }
    EXPECT_EQ(in_step.rays, one_by_one.rays) << scene_file << " group " << group;
    EXPECT_EQ(in_step.dropped, one_by_one.dropped) << scene_file << " group " << group;
  }
}

TEST(PathsInStep, EachPathIsTheSameAsTracedAlone) {
  EnvironmentParams white;
  white.background = vec3(1.0f);
  expect_paths_alike("cornell-box/cornell-box.gltf", {});
  expect_paths_alike("material-extensions/dispersion.gltf", white);
  expect_paths_alike("material-extensions/diffuse-transmission.gltf", white);
  EnvironmentParams sunrise;
  sunrise.image_path = test::scene_path("env/spruit_sunrise_1k.hdr");
  sunrise.image = read_environment_image(sunrise.image_path);
  expect_paths_alike("khronos/DamagedHelmet/glTF-Binary/DamagedHelmet.glb", sunrise);
}

}  // namespace
}  // namespace tessera
