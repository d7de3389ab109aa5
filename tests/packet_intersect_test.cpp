// Camera rays traced as Embree packets (SceneGeometry::intersect_packet) against the same rays
// traced one by one (intersect, rtcIntersect1): every hit the same bit for bit, whichever of
// a pixel's rays share the packet, on shared triangle edges, an alpha-blended surface (whose
// filter runs on packets), instances and a moving instance.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "renderer/geometry/packet_check.h"
#include "renderer/scene/render_scene.h"
#include "tests/scene_builders.h"

namespace tessera {
namespace {

// A finely tessellated sphere (many shared edges), half covered by a BLEND quad of alpha 0.5,
// two placements of one small sphere, and a quad that moves while the shutter is open.
SceneDescription packet_scene(int& blend_material) {
  SceneDescription d;
  d.motion_steps = 2;
  const int grey = test::add_material(d, test::diffuse(vec3(0.5f)));
  Material blend = test::diffuse(vec3(0.2f));
  blend.alpha_mode = AlphaMode::Blend;
  blend.base_color_factor.a = 0.5f;
  blend_material = test::add_material(d, blend);
  test::add_mesh(d, test::make_sphere({0, 0, 0}, 1.0f, 4, grey));
  test::add_mesh(d, test::make_quad({0.6f, 0, 1.2f}, {0.6f, 0, 0}, {0, 1.5f, 0}, blend_material));
  const glm::mat4 left = glm::translate(glm::mat4(1.0f), vec3(-1.4f, 1.0f, 0.5f));
  test::add_mesh(d, test::make_sphere({0, 0, 0}, 0.3f, 2, grey), {left, glm::translate(left, vec3(0, -2.0f, 0))});
  test::add_mesh(d, test::make_quad({0, 0, 0}, {0.3f, 0, 0}, {0, 0.3f, 0}, grey),
                 {glm::translate(glm::mat4(1.0f), vec3(1.2f, -1.2f, 0.8f))});
  d.instances.back().motion = {glm::translate(glm::mat4(1.0f), vec3(1.2f, -0.6f, 0.8f))};
  return d;
}

// The packet's answer for one ray against intersect()'s, field by field.
void expect_same(const SceneGeometry& g, const Ray& ray, const ClosestHit& packet, const vec3& packet_ng) {
  HitRecord single;
  vec3 ng;
  ASSERT_EQ(packet.found, g.intersect(ray, single, &ng));
  if (!packet.found) return;
  const HitRecord& p = packet.hit;
  EXPECT_TRUE(same_bits(p.t, single.t) && same_bits(p.u, single.u) && same_bits(p.v, single.v))
      << p.t << " " << single.t << " " << p.u << " " << single.u << " " << p.v << " " << single.v;
  EXPECT_EQ(p.geom, single.geom);
  EXPECT_EQ(p.prim, single.prim);
  EXPECT_EQ(p.instance, single.instance);
  EXPECT_TRUE(same_bits(p.time, single.time));
  for (int c = 0; c < 3; ++c) EXPECT_TRUE(same_bits(packet_ng[c], ng[c])) << "Ng " << c;
}

TEST(PacketIntersect, EveryHitIsTheSingleRaysWhateverSharesThePacket) {
  int blend_material = -1;
  const RenderScene rs(packet_scene(blend_material), {});
  const SceneGeometry& g = *rs.geometry;
  constexpr int N = SceneGeometry::kPacketSize;
  std::uint32_t moving_instance = RTC_INVALID_GEOMETRY_ID;
  for (const SceneGeometry::PlacedPrimitive& p : g.placed_primitives())
    if (p.moves) moving_instance = p.instance;
  ASSERT_NE(moving_instance, RTC_INVALID_GEOMETRY_ID);
  std::mt19937 gen(11);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  int misses = 0, blended = 0, instanced = 0, moving = 0, hits = 0;
  const vec3 eye(0.1f, 0.05f, 5.0f);
  for (int py = 0; py < 24; ++py) {
    for (int px = 0; px < 24; ++px) {
      // The samples of one pixel: jittered directions through it, each at its own time.
      Ray rays[N];
      for (Ray& r : rays) {
        const vec3 target((px + unit(gen)) / 24.0f * 4.4f - 2.2f, 2.2f - (py + unit(gen)) / 24.0f * 4.4f, 0.0f);
        r = Ray{eye, glm::normalize(target - eye)};
        r.time = unit(gen);
      }
      // The whole pixel, then lanes left idle at random and the rest in shuffled order.
      for (int round = 0; round < 3; ++round) {
        int order[N];
        for (int k = 0; k < N; ++k) order[k] = k;
        int n = N;
        if (round > 0) {
          std::shuffle(order, order + N, gen);
          n = 1 + static_cast<int>(gen() % N);
        }
        Ray packet[N];
        for (int k = 0; k < n; ++k) packet[k] = rays[order[k]];
        ClosestHit found[N];
        vec3 ng[N];
        g.intersect_packet(packet, n, found, ng);
        for (int k = 0; k < n; ++k) {
          expect_same(g, packet[k], found[k], ng[k]);
          if (round > 0) continue;
          if (!found[k].found) {
            ++misses;
            continue;
          }
          ++hits;
          instanced += found[k].hit.instance != RTC_INVALID_GEOMETRY_ID;
          moving += found[k].hit.instance == moving_instance;
          blended += g.surface(packet[k], found[k].hit).material == blend_material;
        }
      }
    }
  }
  // Every kind of hit was compared: the rays' spread covers them all.
  EXPECT_GT(misses, 3000);  // of 9216 rays: 5070 miss, 2957 of the 4146 hits on the blended quad
  EXPECT_GT(blended, 2000);  // (hit wherever its alpha is above 0: which paths pass it is the
  EXPECT_GT(instanced, 250);  // integrator's draw), 425 on instances, 70 on the moving one
  EXPECT_GT(moving, 40);
  EXPECT_GT(hits, 3000);
}

// Packets are traced only on a CPU where Embree's packet kernels agree with its single-ray
// kernel (renderer/geometry/packet_check.h): whenever packets forced on for this richer scene (a
// blended surface, instances, a moving one) give some ray another hit, the check must have
// said no, and RenderScene follows the check.
TEST(PacketIntersect, PacketsAreUsedOnlyWhereTheCheckFoundThemAgreeing) {
  int blend_material = -1;
  RenderScene rs(packet_scene(blend_material), {});
  const bool agree = packets_match_single_rays(rs.device.get(), rs.geometry->moves());
  EXPECT_EQ(rs.geometry->uses_packets(), agree);
  rs.geometry->use_packets(true);
  const SceneGeometry& g = *rs.geometry;
  constexpr int N = SceneGeometry::kPacketSize;
  std::mt19937 gen(23);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const vec3 eye(0.1f, 0.05f, 5.0f);
  int differ = 0, hits = 0;
  for (int p = 0; p < 24 * 24; ++p) {
    const int px = p % 24, py = p / 24;
    Ray rays[N];
    for (Ray& r : rays) {
      const vec3 target((px + unit(gen)) / 24.0f * 4.4f - 2.2f, 2.2f - (py + unit(gen)) / 24.0f * 4.4f, 0.0f);
      r = Ray{eye, glm::normalize(target - eye), 0.0f, std::numeric_limits<float>::infinity(), unit(gen)};
    }
    differ += packet_differences(g, rays, N, &hits);
  }
  EXPECT_GT(hits, 3000);
  EXPECT_TRUE(differ == 0 || !agree) << differ << " of " << hits << " hits differ in packets, yet the check found them agreeing";
}

// Rays aimed at the diagonals of a quad (the edge its two triangles share, where both are hit
// at the same t): Embree's packet traversal may reach the other triangle first; the packet
// still reports the hit the single ray gets.
TEST(PacketIntersect, TiesOnASharedEdgeGoAsForTheSingleRay) {
  SceneDescription d;
  test::add_mesh(d, test::make_quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, test::add_material(d, test::diffuse(vec3(0.5f)))));
  const RenderScene rs(std::move(d), {});
  const SceneGeometry& g = *rs.geometry;
  constexpr int N = SceneGeometry::kPacketSize;
  std::mt19937 gen(5);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  for (int p = 0; p < 400; ++p) {
    const vec3 eye(unit(gen), unit(gen), 3.0f + unit(gen));
    Ray rays[N];
    for (int k = 0; k < N; ++k) {
      const float s = unit(gen);
      rays[k] = Ray{eye, glm::normalize(vec3(s, k % 2 ? s : -s, 0.0f) - eye)};
    }
    ClosestHit found[N];
    vec3 ng[N];
    g.intersect_packet(rays, N, found, ng);
    for (int k = 0; k < N; ++k) {
      ASSERT_TRUE(found[k].found);
      expect_same(g, rays[k], found[k], ng[k]);
    }
  }
}

}  // namespace
}  // namespace tessera
