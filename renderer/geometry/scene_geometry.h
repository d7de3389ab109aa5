// The scene's triangles in Embree: one BVH over the world. A mesh placed once is baked into
// world space in the top-level BVH; a mesh placed several times is built once as its own
// BVH and placed with Embree instances, so memory does not grow with placements.
// An animated scene (SceneDescription::animated) is built as Embree's two-level BVH (scene
// build quality low): each triangle list has its own BVH, kept until update() changes it, and
// the top level is rebuilt over them. So the next frame's description rebuilds only what
// moved; a frame built fresh gets the same BVHs, hence the same image bit for bit.
// Motion blur (SceneDescription::motion_steps > 1): a deforming mesh gets one Embree vertex
// buffer per motion step; a placement that moves is an Embree instance with a transform per
// step in parts (RTCQuaternionDecomposition), so that rotations turn rather than shrink.
// Rays carry their time and Embree intersects the scene as it is then; nothing that moves
// nothing (motion_steps 1, or steps equal to step 0) is built or read as before.
#pragma once

#include <embree3/rtcore.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <memory_resource>
#include <optional>
#include <vector>

#include "renderer/util/cache_line_allocator.h"
#include "renderer/util/ray.h"
#include "renderer/description/scene.h"

namespace tessera {

// Where a hit landed, as Embree reports it, and when (the ray's time).
struct HitRecord {
  float t = 0.0f, u = 0.0f, v = 0.0f;
  std::uint32_t geom = RTC_INVALID_GEOMETRY_ID, prim = 0, instance = RTC_INVALID_GEOMETRY_ID;
  float time = 0.0f;
};

// A ray's closest hit, if it has one.
struct ClosestHit {
  bool found = false;
  HitRecord hit;  // when found
};

// Everything shading needs about a hit point, in world space.
struct SurfaceHit {
  vec3 p;
  vec3 ng;  // unit geometric normal, on the side of the triangle's front face
  vec3 ns;  // unit shading normal (interpolated NORMAL, else ng), same hemisphere as ng
  vec4 tangent{0.0f};  // xyz world tangent, w = bitangent sign; zero when absent
  vec2 uv[2]{vec2(0.0f), vec2(0.0f)};
  vec4 color{1.0f};
  int material = -1;
  float t = 0.0f;
  float extent = 1.0f;  // the triangle's largest |world coordinate|: the scale of p's rounding error
};

// A triangle's texture coordinates at its corners and its material: what its material's
// textures read at any point of it, as surface() gives them (not the vertex colour). An
// emitter keeps its own, so that a light sample evaluates the emission without the mesh
// (placement, indices, coordinates: three dependent cache misses).
struct TextureCorners {
  vec2 uv[2][3]{};  // TEXCOORD_0 and _1 at the three corners; zero where the mesh has none
  int material = -1;
  SurfaceHit at(float u, float v) const;  // u, v: the weights of the second and third corner
};

// The opacity of a material where a ray meets it (alpha MASK and BLEND cut-outs), from the
// texture coordinates and vertex colour there. Materials sit above geometry, so whoever owns
// both hands it in (RenderScene: MaterialTable::opacity).
struct SurfaceOpacity {
  float (*at)(const void* user, int material, const vec2 uv[2], const vec4& color) = nullptr;
  const void* user = nullptr;
};

// What a shadow ray passes at a thin-walled transmissive surface: its straight-through
// transmittance there, as the integrator models it (zero where the surface is not thin).
using ThinTransmittance = vec3 (*)(const void* user, const Ray& ray, const HitRecord& hit);

class SceneGeometry {
 public:
  // What the filters need about their triangles (Embree geometry user data).
  struct FilterView {
    const TriangleMesh* mesh;
    SurfaceOpacity opacity;
    bool alpha_tested;  // alpha MASK or BLEND
    bool transmissive;  // transmission > 0: thin-walled where it has no thickness
    float alpha_at(std::uint32_t prim, float u, float v) const;
  };

  // With `opacity`, triangles whose material is alpha MASK or BLEND get Embree filter
  // functions: every ray (camera, bounce, shadow) sees the same cut-outs (MASK below the
  // cutoff, BLEND of alpha 0); a shadow ray passes a BLEND surface weighted by 1 - alpha,
  // where a closest-hit ray meets it (which of the paths pass is the integrator's choice).
  // Those of transmissive materials get an occlusion filter, so shadow rays pass thin surfaces.
  // Throws std::invalid_argument when motion arrays do not have motion_steps - 1 steps.
  SceneGeometry(const SceneDescription& scene, RTCDevice device, SurfaceOpacity opacity = {});
  ~SceneGeometry();
  SceneGeometry(const SceneGeometry&) = delete;
  SceneGeometry& operator=(const SceneGeometry&) = delete;
  // Cache hints for surface(hit): the hit triangle's indices; then, reading them, its corners'
  // positions and normals. The hits of a camera-ray packet (one pixel's samples, each on
  // another small triangle) prefetched together overlap the misses that surface() would take
  // one after another. Nothing depends on them but the time.
  void prefetch_triangle(const HitRecord& hit) const;
  void prefetch_corners(const HitRecord& hit) const;

  // With `geometric_normal`, also Embree's unnormalised geometric normal (in the hit
  // instance's own space: what a traversal-only pass needs, not shading).
  bool intersect(const Ray& ray, HitRecord& hit, vec3* geometric_normal = nullptr) const;
  // The closest hits of n <= kPacketSize rays traced together (rtcIntersect16, marked coherent:
  // meant for the camera rays of one pixel). Each is what intersect() gives that ray, bit for
  // bit: where packets are used, Embree's packet kernels compute the same t, u, v and normal
  // (renderer/geometry/packet_check.h makes sure), and a hit within kEdgeBand (barycentric) of an
  // edge, where a neighbour ties, is traced again alone. Only
  // a tie between overlapping triangles away from their edges may still go either way, the
  // same way for the same packet (docs/performance.md, "Camera rays as packets").
  // Fewer than kMinPacket rays are traced one by one: a packet of 16 with 4 lanes busy took
  // 1.3-1.5 times as long as 4 single rays, with 8 busy 0.7-1.1 times (docs/performance.md).
  // So are all of them until use_packets(true): where Embree's packets agree with its single
  // rays on this CPU (renderer/geometry/packet_check.h; RenderScene asks).
  static constexpr int kPacketSize = 16, kMinPacket = 8;
  static constexpr float kEdgeBand = 1e-5f;
  void intersect_packet(const Ray* rays, int n, ClosestHit* hits, vec3* normals = nullptr) const;
  void use_packets(bool on) { packets_ = on; }
  bool uses_packets() const { return packets_; }
  // What reaches origin from origin + tmax direction at `time`: 0 behind an opaque surface,
  // else the product of what the surfaces between let through (1 - alpha of a BLEND
  // surface, the straight-through transmittance of a thin transmissive one, from `thin`).
  // Each surface counts once; past kMaxThinCrossings of them the ray is taken as blocked.
  static constexpr int kMaxThinCrossings = 16;
  vec3 transmittance(const vec3& origin, const vec3& direction, float tmax, float time, ThinTransmittance thin,
                     const void* user) const;
  // The surface at the hit, where it is at hit.time.
  SurfaceHit surface(const Ray& ray, const HitRecord& hit) const;
  // The texture coordinates and material of the hit's triangle (geom, instance, prim).
  TextureCorners texture_corners(const HitRecord& hit) const;
  // The world-space corners of the hit's triangle (geom, instance, prim) at hit.time, in the
  // order surface() reads them (its u and v are the weights of the second and third).
  struct Corners {
    vec3 p0, p1, p2;
  };
  Corners corners(const HitRecord& hit) const;

  // Every triangle list where it stands (at the shutter's opening), with the ids a hit on it
  // carries.
  struct PlacedPrimitive {
    std::uint32_t geom, instance;  // as in HitRecord
    const TriangleMesh* mesh;
    glm::mat4 to_world;  // identity for meshes baked into world space
    bool moves;  // its placement moves or its mesh deforms: corners() depend on the time
  };
  std::vector<PlacedPrimitive> placed_primitives() const;
  // Each of those lists' world box over the whole shutter: everywhere its triangles can be
  // while it is open (renderer/geometry/shutter_bounds.cpp).
  std::vector<Bounds3> shutter_bounds() const;

  // Whether `next` (another frame of the same scene, as SceneDescription::animated scenes
  // have) has the structure built here: the same meshes, triangles, attributes and materials,
  // the same placements, and the same of them moving or deforming over the shutter.
  bool can_update(const SceneDescription& next) const;
  // After the description this was built from has taken over next's vertex arrays and
  // placements (the primitives in `changed_primitives` [mesh][primitive], the placements in
  // `changed_instances`), re-reads those and rebuilds their BVHs, and the top level; the rest
  // is kept. Returns the number of triangles whose BVH was rebuilt.
  std::uint64_t update(const std::vector<std::vector<char>>& changed_primitives, const std::vector<char>& changed_instances);

  // Whether anything moves while the shutter is open, and the motion steps the scene has.
  bool moves() const { return moves_; }
  int motion_steps() const { return steps_; }

  std::uint64_t unique_triangles() const { return unique_triangles_; }
  std::uint64_t instanced_triangles() const { return instanced_triangles_; }

 private:
  // One triangle mesh where it stands: world-space data, or object-space data + transform
  // (for a moving instance, its transform at the hit's time).
  struct Placement {
    const TriangleMesh* mesh;
    glm::mat4 to_world{1.0f};
    glm::mat3 normal_to_world{1.0f};
    float orientation = 1.0f;  // -1 where the transform mirrors (negative determinant)
    bool in_world_space = true;
    bool deforms = false;  // the mesh's vertex arrays have motion steps, read at the time
  };
  struct InstanceRecord {  // a top-level Embree instance: a placed multi-primitive mesh
    int mesh;
    int instance;  // in scene_.instances
    glm::mat4 to_world;  // at the shutter's opening
    RTCGeometry moving = nullptr;  // a placement that moves: Embree gives its transform at a time
  };

  void check_motion(const SceneDescription& scene) const;
  bool instance_moves(const Instance& inst) const;
  bool mesh_deforms(const TriangleMesh& mesh) const;
  void add_baked(int mesh_index, int instance);
  void add_instanced(int mesh_index, const std::vector<const Instance*>& placements);
  // `baked`: one of baked_, which Embree then reads in place when it does not deform.
  unsigned attach_triangles(RTCScene target, const TriangleMesh& mesh, bool deforms, bool baked);
  unsigned vertex_steps(const TriangleMesh& mesh, bool deforms) const;  // Embree's vertex buffers
  // Copies the mesh's positions (every motion step Embree has) and indices into geom's buffers.
  void fill_buffers(RTCGeometry geom, const TriangleMesh& mesh, unsigned steps) const;
  void set_instance_transform(RTCGeometry geom, const Instance& inst, bool moving) const;
  void install_filters(RTCGeometry geom, const TriangleMesh& mesh);
  // Where the hit's triangles stand: a baked mesh's placement, or an instance's (at the hit's
  // time) made in `scratch`.
  const Placement& placement(const HitRecord& hit, Placement& scratch) const {
    return hit.instance == RTC_INVALID_GEOMETRY_ID ? top_geometry_[hit.geom] : instance_placement(hit, scratch);
  }
  const Placement& instance_placement(const HitRecord& hit, Placement& scratch) const;
  const TriangleMesh& hit_mesh(const HitRecord& hit) const;
  Corners corners(const Placement& pl, const std::uint32_t* idx, float time) const;  // in pl's space


  const SceneDescription& scene_;
  RTCDevice device_;
  bool packets_ = false;  // intersect_packet traces packets (else each ray alone)
  SurfaceOpacity opacity_;
  std::vector<std::unique_ptr<FilterView>> filter_views_;
  RTCScene top_ = nullptr;
  std::vector<RTCScene> prototypes_;  // one per instanced mesh, indexed like scene_.meshes
  // World-space copies of meshes placed once, their arrays side by side in one block (on
  // huge pages from 2 MiB: surface() reads them at random, and with 4 KiB pages a million
  // triangles' also missed the TLB; docs/performance.md).
  std::vector<std::byte, CacheLineAllocator<std::byte>> baked_block_;
  std::optional<std::pmr::monotonic_buffer_resource> baked_memory_;  // hands out baked_block_, then the heap
  std::vector<TriangleMesh> baked_;
  struct BakedSource {
    int mesh, primitive, instance;
    unsigned geom;  // its top-level id
  };
  std::vector<BakedSource> baked_sources_;  // what each of baked_ was made from
  std::vector<Placement> top_geometry_;  // by top-level geomID (baked triangles)
  std::vector<InstanceRecord> top_instances_;  // by top-level geomID (instances)
  std::vector<bool> top_is_instance_;
  std::vector<std::vector<char>> deforms_;  // [mesh][primitive]: vertex arrays with motion steps
  std::vector<char> instance_moves_;  // [instance]: moves while the shutter is open
  int steps_ = 1;  // motion steps: 1 = no motion blur
  bool moves_ = false;
  std::uint64_t unique_triangles_ = 0, instanced_triangles_ = 0;
};

}  // namespace tessera
