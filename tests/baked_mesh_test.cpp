// The world-space copies SceneGeometry makes of meshes placed once: side by side in one block
// (on a huge-page boundary from 2 MiB), each vertex array with room for the vertex past its
// end that Embree, which reads them in place, may load; and what they hold is the mesh
// moved into the world.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>

#include <glm/gtc/matrix_transform.hpp>

#include "renderer/scene/render_scene.h"
#include "tests/scene_builders.h"

namespace tessera {
namespace {

constexpr std::uintptr_t kHugePage = std::uintptr_t{2} << 20;

// The address range [first, end) of every array of the scene's baked meshes.
struct Span {
  std::uintptr_t first = ~std::uintptr_t{0}, end = 0;
  std::size_t bytes = 0;  // the arrays' own bytes
  template <typename Array>
  void add(const Array& a) {
    if (a.empty()) return;
    first = std::min(first, reinterpret_cast<std::uintptr_t>(a.data()));
    end = std::max(end, reinterpret_cast<std::uintptr_t>(a.data() + a.size()));
    bytes += a.size() * sizeof(a[0]);
  }
};

Span baked_span(const SceneGeometry& g, int& baked) {
  Span s;
  baked = 0;
  for (const SceneGeometry::PlacedPrimitive& pp : g.placed_primitives()) {
    if (pp.instance != RTC_INVALID_GEOMETRY_ID) continue;
    const TriangleMesh& m = *pp.mesh;
    ++baked;
    s.add(m.positions), s.add(m.normals), s.add(m.tangents), s.add(m.texcoords0), s.add(m.texcoords1);
    s.add(m.colors), s.add(m.indices);
    EXPECT_GE(m.positions.capacity(), m.positions.size() + 1) << "no room for Embree's 16-byte load";
  }
  return s;
}

SceneDescription spheres(int subdivisions, bool twice) {
  SceneDescription d;
  const int grey = test::add_material(d, test::diffuse(vec3(0.5f)));
  test::add_mesh(d, test::make_sphere({0, 0, 0}, 1.0f, subdivisions, grey, false, true),
                 {glm::translate(glm::mat4(1.0f), vec3(-1.5f, 0, 0))});
  test::add_mesh(d, test::make_sphere({0, 0, 0}, 0.5f, subdivisions, grey, false, true),
                 {glm::translate(glm::mat4(1.0f), vec3(1.5f, 0, 0))});
  if (twice)  // an instanced mesh: not baked, not in the block
    test::add_mesh(d, test::make_sphere({0, 0, 0}, 0.2f, 2, grey),
                   {glm::translate(glm::mat4(1.0f), vec3(0, 2, 0)), glm::translate(glm::mat4(1.0f), vec3(0, -2, 0))});
  return d;
}

// Two icospheres of 81,920 triangles (1.9 MiB of positions, normals and indices each): one
// block of more than 2 MiB, starting on a huge page; every array inside it, in no more than
// the arrays' bytes plus a little alignment.
TEST(BakedMeshes, LieSideBySideInOneBlockOnAHugePage) {
  const RenderScene rs(spheres(6, true), {});
  int baked = 0;
  const Span s = baked_span(*rs.geometry, baked);
  EXPECT_EQ(baked, 2);
  EXPECT_GT(s.bytes, kHugePage);
  EXPECT_EQ(s.first % kHugePage, 0u);
  EXPECT_LE(s.end - s.first, s.bytes + 2 * 7 * 64 + 2 * sizeof(vec3)) << "arrays outside one block";
}

// A small scene's block starts on a cache line.
TEST(BakedMeshes, ASmallBlockStartsOnACacheLine) {
  const RenderScene rs(spheres(2, false), {});
  int baked = 0;
  const Span s = baked_span(*rs.geometry, baked);
  EXPECT_EQ(baked, 2);
  EXPECT_LT(s.bytes, kHugePage);
  EXPECT_EQ(s.first % 64, 0u);
  EXPECT_LE(s.end - s.first, s.bytes + 2 * 7 * 64 + 2 * sizeof(vec3));
}

// The copy is the mesh in world space: each vertex is the placement times the source's, and
// Embree, reading the copy, finds the sphere where the placement put it (a ray down the x axis
// meets the unit sphere placed at x = -1.5 at distance 10 - 1.5 - 1, within the tessellation).
TEST(BakedMeshes, HoldTheMeshInWorldSpaceWhereEmbreeFindsIt) {
  const SceneDescription d = spheres(3, false);
  const RenderScene rs(d, {});
  const SceneGeometry& g = *rs.geometry;
  for (const SceneGeometry::PlacedPrimitive& pp : g.placed_primitives()) {
    const TriangleMesh& src = d.meshes[static_cast<std::size_t>(pp.geom)].primitives[0];
    const glm::mat4& to_world = d.instances[static_cast<std::size_t>(pp.geom)].object_to_world;
    ASSERT_EQ(pp.mesh->positions.size(), src.positions.size());
    for (std::size_t i = 0; i < src.positions.size(); i += 97)
      EXPECT_EQ(pp.mesh->positions[i], vec3(to_world * vec4(src.positions[i], 1.0f))) << i;
    EXPECT_EQ(pp.mesh->indices, src.indices);
  }
  HitRecord hit;
  ASSERT_TRUE(g.intersect(Ray{vec3(-10.0f, 0.0f, 0.0f), vec3(1.0f, 0.0f, 0.0f)}, hit));
  EXPECT_NEAR(hit.t, 7.5f, 0.02f);
  ASSERT_TRUE(g.intersect(Ray{vec3(10.0f, 0.0f, 0.0f), vec3(-1.0f, 0.0f, 0.0f)}, hit));
  EXPECT_NEAR(hit.t, 8.0f, 0.01f);
}

}  // namespace
}  // namespace tessera
