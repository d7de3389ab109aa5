#include "renderer/geometry/scene_geometry.h"

#include "renderer/geometry/motion.h"

#include <algorithm>
#include <cstring>
#include <map>
#include <stdexcept>
#include <string>

namespace tessera {
namespace {

// An empty mesh whose arrays take their memory from `memory`.
TriangleMesh mesh_in(std::pmr::memory_resource* memory) {
  return TriangleMesh{MeshArray<vec3>(memory), MeshArray<vec3>(memory), MeshArray<vec4>(memory),
                      MeshArray<vec2>(memory), MeshArray<vec2>(memory), MeshArray<vec4>(memory),
                      MeshArray<std::uint32_t>(memory), -1, {}, {}, {}};
}

// What a mesh's arrays take in the block, each rounded up to 64 bytes: more than the block's
// packing (to each element's alignment) needs, so that the copies never spill to the heap.
std::size_t array_bytes(const TriangleMesh& m) {
  auto bytes = [](const auto& a, std::size_t more = 0) { return ((a.size() + more) * sizeof(a[0]) + 63) / 64 * 64; };
  return bytes(m.positions, 1) + bytes(m.normals) + bytes(m.tangents) + bytes(m.texcoords0) + bytes(m.texcoords1) +
         bytes(m.colors) + bytes(m.indices);
}

// Bakes a mesh into world space in `out` (whose arrays keep their memory), each motion step
// too when it deforms (else its motion arrays are left behind). A mirroring transform
// reverses the winding so that the front face (counter-clockwise in the file) stays the front face.
void to_world_space(const TriangleMesh& src, const glm::mat4& m, bool deforms, TriangleMesh& out) {
  out.positions.reserve(src.positions.size() + 1);  // the padding Embree reads past the last vertex
  out = src;  // a polymorphic array's copy assignment keeps the target's memory (and capacity)
  if (!deforms) {
    out.motion_positions = {};
    out.motion_normals = {};
    out.motion_tangents = {};
  }
  const glm::mat3 nm = glm::transpose(glm::inverse(glm::mat3(m)));
  auto points = [&](MeshArray<vec3>& ps) {
    for (vec3& p : ps) p = vec3(m * vec4(p, 1.0f));
  };
  auto normals = [&](MeshArray<vec3>& ns) {
    for (vec3& n : ns) n = nm * n;
  };
  auto tangents = [&](MeshArray<vec4>& ts) {
    for (vec4& t : ts) t = vec4(glm::mat3(m) * vec3(t), t.w);
  };
  points(out.positions);
  normals(out.normals);
  tangents(out.tangents);
  for (auto& step : out.motion_positions) points(step);
  for (auto& step : out.motion_normals) normals(step);
  for (auto& step : out.motion_tangents) tangents(step);
  if (glm::determinant(glm::mat3(m)) < 0.0f)
    for (std::size_t i = 0; i + 2 < out.indices.size(); i += 3) std::swap(out.indices[i + 1], out.indices[i + 2]);
}

// A transform in Embree's parts. Consecutive steps' quaternions are kept in one hemisphere
// (q and -q are the same rotation), so that Embree's slerp and its motion bounds agree on
// the short way round.
RTCQuaternionDecomposition embree_parts(const glm::mat4& m, glm::quat& previous) {
  AffineParts p = decompose(m);
  if (glm::dot(p.rotation, previous) < 0.0f) p.rotation = -p.rotation;
  previous = p.rotation;
  RTCQuaternionDecomposition qd;
  rtcInitQuaternionDecomposition(&qd);
  rtcQuaternionDecompositionSetScale(&qd, p.upper[0][0], p.upper[1][1], p.upper[2][2]);
  rtcQuaternionDecompositionSetSkew(&qd, p.upper[1][0], p.upper[2][0], p.upper[2][1]);
  rtcQuaternionDecompositionSetQuaternion(&qd, p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z);
  rtcQuaternionDecompositionSetTranslation(&qd, p.translation.x, p.translation.y, p.translation.z);
  return qd;
}

// Whether any later motion step differs from step 0.
template <typename T>
bool steps_differ(const MeshArray<T>& step0, const std::vector<MeshArray<T>>& later) {
  return std::any_of(later.begin(), later.end(), [&](const MeshArray<T>& step) { return step != step0; });
}

// A tangent frame from the triangle's UV parameterisation, for normal maps on meshes without
// TANGENT. v is flipped: glTF's texture origin is the top-left, while tangent space (as
// MikkTSpace builds it for glTF) has the bitangent pointing up the image.
vec4 face_tangent(const vec3& p0, const vec3& p1, const vec3& p2, vec2 t0, vec2 t1, vec2 t2, const vec3& n) {
  const vec3 e1 = p1 - p0, e2 = p2 - p0;
  const vec2 d1(t1.x - t0.x, t0.y - t1.y), d2(t2.x - t0.x, t0.y - t2.y);
  const float det = d1.x * d2.y - d1.y * d2.x;
  if (!(std::fabs(det) > 1e-20f)) return vec4(0.0f);
  const vec3 t = (e1 * d2.y - e2 * d1.y) / det, b = (e2 * d1.x - e1 * d2.x) / det;
  if (!all_finite(t) || glm::dot(t, t) == 0.0f) return vec4(0.0f);
  return vec4(glm::normalize(t), glm::dot(glm::cross(n, t), b) < 0.0f ? -1.0f : 1.0f);
}

template <typename T>
T interpolate(const MeshArray<T>& values, const std::uint32_t* idx, float u, float v) {
  return (1.0f - u - v) * values[idx[0]] + u * values[idx[1]] + v * values[idx[2]];
}

// The same for an attribute with motion steps, at a time between two of them.
template <typename T>
T interpolate(const MeshArray<T>& step0, const std::vector<MeshArray<T>>& later, const std::uint32_t* idx,
              float u, float v, MotionSegment seg) {
  return (1.0f - u - v) * attribute_at(step0, later, idx[0], seg) + u * attribute_at(step0, later, idx[1], seg) +
         v * attribute_at(step0, later, idx[2], seg);
}

}  // namespace

SceneGeometry::SceneGeometry(const SceneDescription& scene, RTCDevice device, SurfaceOpacity opacity)
    : scene_(scene), device_(device), opacity_(opacity), steps_(std::max(scene.motion_steps, 1)) {
  if (steps_ > 1) check_motion(scene);
  deforms_.resize(scene.meshes.size());
  for (std::size_t m = 0; m < scene.meshes.size(); ++m)
    for (const TriangleMesh& prim : scene.meshes[m].primitives) deforms_[m].push_back(mesh_deforms(prim));
  for (const Instance& inst : scene.instances) instance_moves_.push_back(instance_moves(inst));
  top_ = rtcNewScene(device_);
  // Dynamic with low quality selects Embree's two-level builder, which keeps the BVH of every
  // triangle list that no update touched (either alone still rebuilds everything); each list's
  // own BVH is a full SAH build (the geometry's quality, medium).
  rtcSetSceneFlags(top_, scene.animated ? RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_DYNAMIC : RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(top_, scene.animated ? RTC_BUILD_QUALITY_LOW : RTC_BUILD_QUALITY_HIGH);
  std::map<int, std::vector<const Instance*>> by_mesh;
  for (const Instance& inst : scene.instances) by_mesh[inst.mesh].push_back(&inst);
  std::size_t baked_count = 0;
  auto baked = [&](const std::vector<const Instance*>& placements) {
    return placements.size() == 1 && !instance_moves(*placements[0]);  // a moving one is an instance
  };
  std::size_t baked_bytes = 0;
  for (const auto& [mesh, placements] : by_mesh) {
    if (!baked(placements)) continue;
    baked_count += scene.meshes[mesh].primitives.size();
    for (const TriangleMesh& prim : scene.meshes[mesh].primitives) baked_bytes += array_bytes(prim);
  }
  baked_.reserve(baked_count);  // Placement keeps pointers into baked_
  baked_block_.resize(baked_bytes);
  if (baked_bytes > 0) baked_memory_.emplace(baked_block_.data(), baked_block_.size(), std::pmr::new_delete_resource());
  else baked_memory_.emplace(std::pmr::new_delete_resource());
  prototypes_.assign(scene.meshes.size(), nullptr);
  for (const auto& [mesh, placements] : by_mesh) {
    std::uint64_t tris = 0;
    for (const TriangleMesh& prim : scene.meshes[mesh].primitives) tris += prim.triangle_count();
    unique_triangles_ += tris;
    instanced_triangles_ += tris * placements.size();
    if (baked(placements)) add_baked(mesh, static_cast<int>(placements[0] - scene.instances.data()));
    else add_instanced(mesh, placements);
  }
  rtcCommitScene(top_);
  if (rtcGetDeviceError(device_) != RTC_ERROR_NONE)
    throw std::runtime_error("Embree could not build the scene's BVH");
}

SceneGeometry::~SceneGeometry() {
  for (const InstanceRecord& inst : top_instances_)
    if (inst.moving) rtcReleaseGeometry(inst.moving);
  for (RTCScene s : prototypes_)
    if (s) rtcReleaseScene(s);
  if (top_) rtcReleaseScene(top_);
}

void SceneGeometry::check_motion(const SceneDescription& scene) const {
  const std::size_t later = static_cast<std::size_t>(steps_ - 1);
  auto fail = [&](const std::string& what) {
    throw std::invalid_argument(what + " does not have motion_steps - 1 = " + std::to_string(later) + " motion steps");
  };
  for (std::size_t i = 0; i < scene.instances.size(); ++i)
    if (!scene.instances[i].motion.empty() && scene.instances[i].motion.size() != later) fail("instance " + std::to_string(i));
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    for (std::size_t p = 0; p < scene.meshes[m].primitives.size(); ++p) {
      const TriangleMesh& t = scene.meshes[m].primitives[p];
      const std::string name = "mesh " + std::to_string(m) + " primitive " + std::to_string(p);
      auto check = [&](const auto& step0, const auto& steps, const char* what) {
        if (steps.empty()) return;
        if (steps.size() != later) fail(name + "'s " + what);
        for (const auto& step : steps)
          if (step.size() != step0.size() || step0.size() != t.positions.size())
            throw std::invalid_argument(name + "'s " + what + " at a motion step are not one per vertex");
      };
      check(t.positions, t.motion_positions, "positions");
      check(t.normals, t.motion_normals, "normals");
      check(t.tangents, t.motion_tangents, "tangents");
    }
  }
}

namespace {

// Same triangles, attributes, material and motion steps; the vertex values may differ.
bool same_layout(const TriangleMesh& a, const TriangleMesh& b) {
  auto steps_alike = [](const auto& x, const auto& y) {
    if (x.size() != y.size()) return false;
    for (std::size_t k = 0; k < x.size(); ++k)
      if (x[k].size() != y[k].size()) return false;
    return true;
  };
  return a.indices == b.indices && a.material == b.material && a.positions.size() == b.positions.size() &&
         a.normals.size() == b.normals.size() && a.tangents.size() == b.tangents.size() &&
         a.texcoords0.size() == b.texcoords0.size() && a.texcoords1.size() == b.texcoords1.size() &&
         a.colors.size() == b.colors.size() && steps_alike(a.motion_positions, b.motion_positions) &&
         steps_alike(a.motion_normals, b.motion_normals) && steps_alike(a.motion_tangents, b.motion_tangents);
}

}  // namespace

bool SceneGeometry::can_update(const SceneDescription& next) const {
  if (std::max(next.motion_steps, 1) != steps_ || next.animated != scene_.animated ||
      next.meshes.size() != scene_.meshes.size() || next.instances.size() != scene_.instances.size())
    return false;
  for (std::size_t i = 0; i < next.instances.size(); ++i)
    if (next.instances[i].mesh != scene_.instances[i].mesh || instance_moves(next.instances[i]) != (instance_moves_[i] != 0))
      return false;
  for (std::size_t m = 0; m < next.meshes.size(); ++m) {
    const auto &now = scene_.meshes[m].primitives, &then = next.meshes[m].primitives;
    if (now.size() != then.size()) return false;
    for (std::size_t p = 0; p < now.size(); ++p)
      if (!same_layout(now[p], then[p]) || mesh_deforms(then[p]) != (deforms_[m][p] != 0)) return false;
  }
  return true;
}

std::uint64_t SceneGeometry::update(const std::vector<std::vector<char>>& changed_primitives,
                                    const std::vector<char>& changed_instances) {
  std::uint64_t rebuilt = 0;
  for (std::size_t k = 0; k < baked_.size(); ++k) {
    const BakedSource& src = baked_sources_[k];
    if (!changed_primitives[src.mesh][src.primitive] && !changed_instances[src.instance]) continue;
    const bool deforms = deforms_[src.mesh][src.primitive];
    to_world_space(scene_.meshes[src.mesh].primitives[src.primitive], scene_.instances[src.instance].object_to_world,
                   deforms, baked_[k]);  // the same layout: in the arrays it has
    RTCGeometry geom = rtcGetGeometry(top_, src.geom);
    fill_buffers(geom, baked_[k], vertex_steps(baked_[k], deforms));
    rtcCommitGeometry(geom);
    rebuilt += baked_[k].triangle_count();
  }
  std::vector<char> reshaped(scene_.meshes.size(), 0);  // an instanced mesh whose BVH was rebuilt
  for (std::size_t m = 0; m < prototypes_.size(); ++m) {
    if (!prototypes_[m]) continue;
    const auto& prims = scene_.meshes[m].primitives;
    for (std::size_t p = 0; p < prims.size(); ++p) {
      if (!changed_primitives[m][p]) continue;
      RTCGeometry geom = rtcGetGeometry(prototypes_[m], static_cast<unsigned>(p));
      fill_buffers(geom, prims[p], vertex_steps(prims[p], deforms_[m][p]));
      rtcCommitGeometry(geom);
      rebuilt += prims[p].triangle_count();
      reshaped[m] = 1;
    }
    if (reshaped[m]) rtcCommitScene(prototypes_[m]);
  }
  for (std::uint32_t id = 0; id < top_is_instance_.size(); ++id) {
    if (!top_is_instance_[id]) continue;
    InstanceRecord& rec = top_instances_[id];
    if (!changed_instances[rec.instance] && !reshaped[rec.mesh]) continue;
    const Instance& inst = scene_.instances[rec.instance];
    RTCGeometry geom = rtcGetGeometry(top_, id);
    set_instance_transform(geom, inst, instance_moves_[rec.instance]);
    rtcCommitGeometry(geom);
    rec.to_world = inst.object_to_world;
  }
  rtcCommitScene(top_);
  if (rtcGetDeviceError(device_) != RTC_ERROR_NONE) throw std::runtime_error("Embree could not update the scene's BVH");
  return rebuilt;
}

bool SceneGeometry::instance_moves(const Instance& inst) const {
  return steps_ > 1 && std::any_of(inst.motion.begin(), inst.motion.end(),
                                   [&](const glm::mat4& m) { return m != inst.object_to_world; });
}

bool SceneGeometry::mesh_deforms(const TriangleMesh& mesh) const {
  return steps_ > 1 && (steps_differ(mesh.positions, mesh.motion_positions) ||
                        steps_differ(mesh.normals, mesh.motion_normals) ||
                        steps_differ(mesh.tangents, mesh.motion_tangents));
}

unsigned SceneGeometry::attach_triangles(RTCScene target, const TriangleMesh& mesh, bool deforms, bool baked) {
  RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
  const unsigned steps = vertex_steps(mesh, deforms);
  if (steps > 1) rtcSetGeometryTimeStepCount(geom, steps);
  if (baked && steps == 1) {
    // A baked copy is ours to keep as it is: Embree reads it where it lies (padded by a vertex
    // for Embree's 16-byte loads: to_world_space) instead of a copy of its own.
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, mesh.positions.data(), 0,
                               sizeof(vec3), mesh.positions.size());
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, mesh.indices.data(), 0,
                               3 * sizeof(std::uint32_t), mesh.triangle_count());
  } else {
    // Embree may read 16 bytes at the last vertex: its own buffers are padded for that.
    bool allocated = true;
    for (unsigned k = 0; k < steps; ++k)
      allocated = allocated && rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, k, RTC_FORMAT_FLOAT3,
                                                       3 * sizeof(float), mesh.positions.size());
    allocated = allocated && rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                     3 * sizeof(std::uint32_t), mesh.triangle_count());
    if (!allocated) {
      rtcReleaseGeometry(geom);
      throw std::runtime_error("Embree could not allocate geometry buffers (out of memory?)");
    }
    fill_buffers(geom, mesh, steps);
  }
  install_filters(geom, mesh);
  rtcCommitGeometry(geom);
  const unsigned id = rtcAttachGeometry(target, geom);
  rtcReleaseGeometry(geom);
  return id;
}

unsigned SceneGeometry::vertex_steps(const TriangleMesh& mesh, bool deforms) const {
  // One vertex buffer per motion step when the positions move; Embree interpolates them.
  return deforms && !mesh.motion_positions.empty() ? static_cast<unsigned>(steps_) : 1u;
}

void SceneGeometry::fill_buffers(RTCGeometry geom, const TriangleMesh& mesh, unsigned steps) const {
  auto fill = [&](RTCBufferType type, unsigned slot, const void* data, std::size_t bytes) {
    void* buffer = rtcGetGeometryBufferData(geom, type, slot);
    if (buffer != data) std::memcpy(buffer, data, bytes);  // else shared: it is the data
    rtcUpdateGeometryBuffer(geom, type, slot);
  };
  for (unsigned k = 0; k < steps; ++k) {
    const MeshArray<vec3>& positions = k == 0 ? mesh.positions : mesh.motion_positions[k - 1];
    fill(RTC_BUFFER_TYPE_VERTEX, k, positions.data(), positions.size() * sizeof(vec3));
  }
  // Indices too: a placement that turns mirroring reverses the winding of a baked copy.
  fill(RTC_BUFFER_TYPE_INDEX, 0, mesh.indices.data(), mesh.indices.size() * sizeof(std::uint32_t));
}

void SceneGeometry::set_instance_transform(RTCGeometry geom, const Instance& inst, bool moving) const {
  if (!moving) {
    rtcSetGeometryTransform(geom, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &inst.object_to_world[0][0]);
    return;
  }
  glm::quat previous(1.0f, 0.0f, 0.0f, 0.0f);
  for (int k = 0; k < steps_; ++k) {
    const RTCQuaternionDecomposition qd = embree_parts(k == 0 ? inst.object_to_world : inst.motion[k - 1], previous);
    rtcSetGeometryTransformQuaternion(geom, static_cast<unsigned>(k), &qd);
  }
}

namespace {

// A shadow ray's query: Embree hands the context's address to the occlusion filters.
struct ShadowQuery {
  RTCIntersectContext embree;  // first, so that the filters can cast back
  ThinTransmittance thin = nullptr;
  const void* user = nullptr;
  vec3 transmittance{1.0f};
  // Surfaces already counted: with spatial splits (build quality high) Embree may report the
  // same triangle more than once.
  std::uint32_t seen[SceneGeometry::kMaxThinCrossings][3];
  int seen_count = 0;
  bool first_time(std::uint32_t inst, std::uint32_t geom, std::uint32_t prim) {
    for (int k = 0; k < seen_count; ++k)
      if (seen[k][0] == inst && seen[k][1] == geom && seen[k][2] == prim) return false;
    seen[seen_count][0] = inst;
    seen[seen_count][1] = geom;
    seen[seen_count][2] = prim;
    ++seen_count;
    return true;
  }
};

// Embree filter for rays that look for the closest hit: rejects a hit where the surface is
// absent (MASK below the cutoff, BLEND of alpha 0). A BLEND surface in between is hit: the
// integrator chooses to pass it with probability 1 - alpha, with a draw of the path's sampler.
void alpha_filter(const RTCFilterFunctionNArguments* args) {
  const auto* view = static_cast<const SceneGeometry::FilterView*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const std::uint32_t prim = RTCHitN_primID(args->hit, args->N, i);
    const float u = RTCHitN_u(args->hit, args->N, i), v = RTCHitN_v(args->hit, args->N, i);
    if (!(view->alpha_at(prim, u, v) > 0.0f)) args->valid[i] = 0;
  }
}

// Embree filter for shadow rays: multiplies what the surface lets through into the query
// and rejects the hit (traversal goes on) unless nothing gets through any more.
void shadow_filter(const RTCFilterFunctionNArguments* args) {
  const auto* view = static_cast<const SceneGeometry::FilterView*>(args->geometryUserPtr);
  auto* query = reinterpret_cast<ShadowQuery*>(const_cast<RTCIntersectContext*>(args->context));
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    HitRecord hit;
    hit.t = RTCRayN_tfar(args->ray, args->N, i);
    hit.u = RTCHitN_u(args->hit, args->N, i);
    hit.v = RTCHitN_v(args->hit, args->N, i);
    hit.geom = RTCHitN_geomID(args->hit, args->N, i);
    hit.prim = RTCHitN_primID(args->hit, args->N, i);
    hit.instance = RTCHitN_instID(args->hit, args->N, i, 0);
    hit.time = RTCRayN_time(args->ray, args->N, i);
    if (query->seen_count == SceneGeometry::kMaxThinCrossings) continue;  // too many: taken as blocked
    if (!query->first_time(hit.instance, hit.geom, hit.prim)) {
      args->valid[i] = 0;
      continue;
    }
    const float alpha = view->alpha_tested ? view->alpha_at(hit.prim, hit.u, hit.v) : 1.0f;
    vec3 through(1.0f - alpha);
    if (alpha > 0.0f && view->transmissive) {
      Ray ray{{RTCRayN_org_x(args->ray, args->N, i), RTCRayN_org_y(args->ray, args->N, i),
               RTCRayN_org_z(args->ray, args->N, i)},
              {RTCRayN_dir_x(args->ray, args->N, i), RTCRayN_dir_y(args->ray, args->N, i),
               RTCRayN_dir_z(args->ray, args->N, i)}};
      ray.time = hit.time;
      through += alpha * query->thin(query->user, ray, hit);
    }
    query->transmittance *= through;
    if (max_component(query->transmittance) > 0.0f) args->valid[i] = 0;
  }
}

}  // namespace

namespace {

// What a material's textures read at (u, v) of the triangle idx: its texture coordinates and
// vertex colour (left as they are where the mesh has none).
void texture_attributes(const TriangleMesh& m, const std::uint32_t* idx, float u, float v, vec2 uv[2], vec4& color) {
  if (!m.texcoords0.empty()) uv[0] = interpolate(m.texcoords0, idx, u, v);
  if (!m.texcoords1.empty()) uv[1] = interpolate(m.texcoords1, idx, u, v);
  if (!m.colors.empty()) color = interpolate(m.colors, idx, u, v);
}

}  // namespace

float SceneGeometry::FilterView::alpha_at(std::uint32_t prim, float u, float v) const {
  vec2 uv[2] = {vec2(0.0f), vec2(0.0f)};
  vec4 color(1.0f);
  texture_attributes(*mesh, &mesh->indices[3 * prim], u, v, uv, color);
  return opacity.at(opacity.user, mesh->material, uv, color);
}

void SceneGeometry::install_filters(RTCGeometry geom, const TriangleMesh& mesh) {
  if (!opacity_.at || mesh.material < 0) return;
  const Material& m = scene_.materials[mesh.material];
  const bool alpha_tested = m.alpha_mode != AlphaMode::Opaque, transmissive = m.transmission_factor > 0.0f;
  if (!alpha_tested && !transmissive) return;
  filter_views_.push_back(std::make_unique<FilterView>(FilterView{&mesh, opacity_, alpha_tested, transmissive}));
  rtcSetGeometryUserData(geom, filter_views_.back().get());
  if (alpha_tested) rtcSetGeometryIntersectFilterFunction(geom, alpha_filter);
  rtcSetGeometryOccludedFilterFunction(geom, shadow_filter);
}

void SceneGeometry::add_baked(int mesh_index, int instance) {
  const Mesh& mesh = scene_.meshes[mesh_index];
  const std::vector<char>& deforms = deforms_[mesh_index];
  for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
    baked_.push_back(mesh_in(&*baked_memory_));
    to_world_space(mesh.primitives[p], scene_.instances[instance].object_to_world, deforms[p], baked_.back());
    const unsigned id = attach_triangles(top_, baked_.back(), deforms[p], true);
    baked_sources_.push_back({mesh_index, static_cast<int>(p), instance, id});
    top_geometry_.resize(id + 1, Placement{nullptr});
    top_is_instance_.resize(id + 1, false);
    top_geometry_[id] = Placement{&baked_.back()};
    top_geometry_[id].deforms = deforms[p];
    moves_ = moves_ || deforms[p];
  }
}

void SceneGeometry::add_instanced(int mesh_index, const std::vector<const Instance*>& placements) {
  RTCScene proto = rtcNewScene(device_);
  rtcSetSceneFlags(proto, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(proto, RTC_BUILD_QUALITY_HIGH);
  const auto& prims = scene_.meshes[mesh_index].primitives;
  for (std::size_t p = 0; p < prims.size(); ++p) {
    attach_triangles(proto, prims[p], deforms_[mesh_index][p], false);
    moves_ = moves_ || deforms_[mesh_index][p];
  }
  rtcCommitScene(proto);
  prototypes_[mesh_index] = proto;
  for (const Instance* inst : placements) {
    RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(geom, proto);
    const int index = static_cast<int>(inst - scene_.instances.data());
    const bool moving = instance_moves_[index];
    if (moving) rtcSetGeometryTimeStepCount(geom, static_cast<unsigned>(steps_));
    set_instance_transform(geom, *inst, moving);
    moves_ = moves_ || moving;
    rtcCommitGeometry(geom);
    const unsigned id = rtcAttachGeometry(top_, geom);
    if (!moving) rtcReleaseGeometry(geom);  // a moving one is kept, to ask for its transform at a time
    top_instances_.resize(id + 1);
    top_is_instance_.resize(id + 1, false);
    top_instances_[id] = {mesh_index, index, inst->object_to_world, moving ? geom : nullptr};
    top_is_instance_[id] = true;
  }
}

std::vector<SceneGeometry::PlacedPrimitive> SceneGeometry::placed_primitives() const {
  std::vector<PlacedPrimitive> out;
  for (std::uint32_t id = 0; id < top_is_instance_.size(); ++id) {
    if (!top_is_instance_[id]) {
      const Placement& pl = top_geometry_[id];
      if (pl.mesh) out.push_back({id, RTC_INVALID_GEOMETRY_ID, pl.mesh, glm::mat4(1.0f), pl.deforms});
      continue;
    }
    const InstanceRecord& inst = top_instances_[id];
    const auto& prims = scene_.meshes[inst.mesh].primitives;
    for (std::uint32_t g = 0; g < prims.size(); ++g)
      out.push_back({g, id, &prims[g], inst.to_world, inst.moving != nullptr || deforms_[inst.mesh][g]});
  }
  return out;
}

bool SceneGeometry::intersect(const Ray& ray, HitRecord& hit, vec3* geometric_normal) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh;
  rh.ray.org_x = ray.origin.x;
  rh.ray.org_y = ray.origin.y;
  rh.ray.org_z = ray.origin.z;
  rh.ray.dir_x = ray.direction.x;
  rh.ray.dir_y = ray.direction.y;
  rh.ray.dir_z = ray.direction.z;
  rh.ray.tnear = ray.tmin;
  rh.ray.tfar = ray.tmax;
  rh.ray.time = ray.time;
  rh.ray.mask = 0xffffffffu;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(top_, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  hit = {rh.ray.tfar, rh.hit.u, rh.hit.v, rh.hit.geomID, rh.hit.primID, rh.hit.instID[0], rh.ray.time};
  if (geometric_normal) *geometric_normal = vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
  return true;
}

void SceneGeometry::intersect_packet(const Ray* rays, int n, ClosestHit* hits, vec3* normals) const {
  if (n < kMinPacket || !packets_) {  // the same hits, without a mostly idle packet's cost
    for (int i = 0; i < n; ++i) hits[i].found = intersect(rays[i], hits[i].hit, normals ? &normals[i] : nullptr);
    return;
  }
  constexpr int N = kPacketSize;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  alignas(64) int valid[N];
  alignas(64) RTCRayHit16 rh;
  for (int i = 0; i < N; ++i) {
    valid[i] = i < n ? -1 : 0;
    const Ray& ray = rays[i < n ? i : 0];  // idle lanes hold a copy, which Embree ignores
    rh.ray.org_x[i] = ray.origin.x;
    rh.ray.org_y[i] = ray.origin.y;
    rh.ray.org_z[i] = ray.origin.z;
    rh.ray.dir_x[i] = ray.direction.x;
    rh.ray.dir_y[i] = ray.direction.y;
    rh.ray.dir_z[i] = ray.direction.z;
    rh.ray.tnear[i] = ray.tmin;
    rh.ray.tfar[i] = ray.tmax;
    rh.ray.time[i] = ray.time;
    rh.ray.mask[i] = 0xffffffffu;
    rh.ray.id[i] = static_cast<unsigned>(i);
    rh.ray.flags[i] = 0;
    rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
  }
  rtcIntersect16(valid, top_, &context, &rh);
  for (int i = 0; i < n; ++i) {
    hits[i].found = rh.hit.geomID[i] != RTC_INVALID_GEOMETRY_ID;
    if (!hits[i].found) continue;
    // On a triangle's edge the neighbour across it is hit at the same t, and of two equal hits
    // Embree keeps the first it visits: the packet's traversal order may pick the other one.
    // Such a ray is traced again alone, so that it gets the hit intersect() gives it.
    const float u = rh.hit.u[i], v = rh.hit.v[i];
    if (std::min(std::min(u, v), 1.0f - u - v) < kEdgeBand) {
      hits[i].found = intersect(rays[i], hits[i].hit, normals ? &normals[i] : nullptr);
      continue;
    }
    hits[i].hit = {rh.ray.tfar[i], rh.hit.u[i], rh.hit.v[i], rh.hit.geomID[i], rh.hit.primID[i], rh.hit.instID[0][i], rh.ray.time[i]};
    if (normals) normals[i] = vec3(rh.hit.Ng_x[i], rh.hit.Ng_y[i], rh.hit.Ng_z[i]);
  }
}

vec3 SceneGeometry::transmittance(const vec3& origin, const vec3& direction, float tmax, float time,
                                  ThinTransmittance thin, const void* user) const {
  ShadowQuery query;
  rtcInitIntersectContext(&query.embree);
  query.thin = thin;
  query.user = user;
  RTCRay ray;
  ray.org_x = origin.x;
  ray.org_y = origin.y;
  ray.org_z = origin.z;
  ray.dir_x = direction.x;
  ray.dir_y = direction.y;
  ray.dir_z = direction.z;
  ray.tnear = 0.0f;
  ray.tfar = tmax;
  ray.time = time;
  ray.mask = 0xffffffffu;
  ray.id = 0;
  ray.flags = 0;
  rtcOccluded1(top_, &query.embree, &ray);
  return ray.tfar < 0.0f ? vec3(0.0f) : query.transmittance;  // Embree sets tfar to -inf on a hit
}

const SceneGeometry::Placement& SceneGeometry::instance_placement(const HitRecord& hit, Placement& scratch) const {
  const InstanceRecord& inst = top_instances_[hit.instance];
  scratch.mesh = &hit_mesh(hit);
  scratch.to_world = inst.to_world;
  if (inst.moving) rtcGetGeometryTransform(inst.moving, hit.time, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &scratch.to_world[0][0]);
  scratch.normal_to_world = glm::transpose(glm::inverse(glm::mat3(inst.to_world)));
  scratch.orientation = glm::determinant(glm::mat3(inst.to_world)) < 0.0f ? -1.0f : 1.0f;
  scratch.in_world_space = false;
  scratch.deforms = steps_ > 1 && deforms_[inst.mesh][hit.geom];
  return scratch;
}

const TriangleMesh& SceneGeometry::hit_mesh(const HitRecord& hit) const {
  if (hit.instance == RTC_INVALID_GEOMETRY_ID) return *top_geometry_[hit.geom].mesh;
  return scene_.meshes[top_instances_[hit.instance].mesh].primitives[hit.geom];
}

void SceneGeometry::prefetch_triangle(const HitRecord& hit) const {
  __builtin_prefetch(&hit_mesh(hit).indices[3 * hit.prim]);
}

void SceneGeometry::prefetch_corners(const HitRecord& hit) const {
  const TriangleMesh& m = hit_mesh(hit);
  const std::uint32_t* idx = &m.indices[3 * hit.prim];
  for (int k = 0; k < 3; ++k) {
    __builtin_prefetch(&m.positions[idx[k]]);
    if (!m.normals.empty()) __builtin_prefetch(&m.normals[idx[k]]);
  }
}

SceneGeometry::Corners SceneGeometry::corners(const Placement& pl, const std::uint32_t* idx, float time) const {
  const TriangleMesh& m = *pl.mesh;
  Corners c;
  if (pl.deforms && !m.motion_positions.empty()) {
    const MotionSegment seg = motion_segment(time, steps_);
    c.p0 = attribute_at(m.positions, m.motion_positions, idx[0], seg);
    c.p1 = attribute_at(m.positions, m.motion_positions, idx[1], seg);
    c.p2 = attribute_at(m.positions, m.motion_positions, idx[2], seg);
  } else {
    c.p0 = m.positions[idx[0]];
    c.p1 = m.positions[idx[1]];
    c.p2 = m.positions[idx[2]];
  }
  return c;
}

SceneGeometry::Corners SceneGeometry::corners(const HitRecord& hit) const {
  Placement scratch{nullptr};
  const Placement& pl = placement(hit, scratch);
  Corners c = corners(pl, &pl.mesh->indices[3 * hit.prim], hit.time);
  if (!pl.in_world_space) {
    c.p0 = vec3(pl.to_world * vec4(c.p0, 1.0f));
    c.p1 = vec3(pl.to_world * vec4(c.p1, 1.0f));
    c.p2 = vec3(pl.to_world * vec4(c.p2, 1.0f));
  }
  return c;
}

SurfaceHit SceneGeometry::surface(const Ray& ray, const HitRecord& hit) const {
  Placement scratch{nullptr};
  const Placement& pl = placement(hit, scratch);
  const TriangleMesh& m = *pl.mesh;
  const std::uint32_t* idx = &m.indices[3 * hit.prim];
  vec3 p0, p1, p2;
  if (!pl.deforms) {
    p0 = m.positions[idx[0]];
    p1 = m.positions[idx[1]];
    p2 = m.positions[idx[2]];
  } else {  // vertex attributes with motion steps are read at the hit's time
    const Corners c = corners(pl, idx, hit.time);
    p0 = c.p0;
    p1 = c.p1;
    p2 = c.p2;
  }
  if (!pl.in_world_space) {
    p0 = vec3(pl.to_world * vec4(p0, 1.0f));
    p1 = vec3(pl.to_world * vec4(p1, 1.0f));
    p2 = vec3(pl.to_world * vec4(p2, 1.0f));
  }
  const bool timed = pl.deforms;
  SurfaceHit s;
  s.t = hit.t;
  const vec3 largest = glm::max(glm::abs(p0), glm::max(glm::abs(p1), glm::abs(p2)));
  s.extent = max_component(largest);
  s.p = (1.0f - hit.u - hit.v) * p0 + hit.u * p1 + hit.v * p2;
  vec3 ng = glm::cross(p1 - p0, p2 - p0) * pl.orientation;
  const float len = glm::length(ng);
  // Both from the value, not one from the other: that read back two stores as one load,
  // which the CPU cannot forward (a stall of 15% of this function on MetalRoughSpheres).
  const vec3 unit_ng = len > 0.0f && std::isfinite(len) ? ng / len : -ray.direction;
  s.ng = unit_ng;
  s.ns = unit_ng;
  if (!m.normals.empty()) {
    vec3 n = timed && !m.motion_normals.empty()
                 ? interpolate(m.normals, m.motion_normals, idx, hit.u, hit.v, motion_segment(hit.time, steps_))
                 : interpolate(m.normals, idx, hit.u, hit.v);
    if (!pl.in_world_space) n = pl.normal_to_world * n;
    const float nl = glm::length(n);
    if (nl > 0.0f && std::isfinite(nl)) s.ns = n / nl;
    if (glm::dot(s.ns, s.ng) < 0.0f) s.ng = -s.ng;  // trust the author's normals for the side
  }
  if (!m.tangents.empty()) {
    vec4 t = timed && !m.motion_tangents.empty()
                 ? interpolate(m.tangents, m.motion_tangents, idx, hit.u, hit.v, motion_segment(hit.time, steps_))
                 : interpolate(m.tangents, idx, hit.u, hit.v);
    vec3 tw = pl.in_world_space ? vec3(t) : glm::mat3(pl.to_world) * vec3(t);
    s.tangent = vec4(tw, t.w < 0.0f ? -1.0f : 1.0f);
  }
  texture_attributes(m, idx, hit.u, hit.v, s.uv, s.color);
  if (m.tangents.empty() && !m.texcoords0.empty())
    s.tangent = face_tangent(p0, p1, p2, m.texcoords0[idx[0]], m.texcoords0[idx[1]], m.texcoords0[idx[2]], s.ns);
  s.material = m.material;
  return s;
}

TextureCorners SceneGeometry::texture_corners(const HitRecord& hit) const {
  Placement scratch{nullptr};
  const TriangleMesh& m = *placement(hit, scratch).mesh;
  const std::uint32_t* idx = &m.indices[3 * hit.prim];
  TextureCorners c;
  for (int k = 0; k < 3; ++k) {
    if (!m.texcoords0.empty()) c.uv[0][k] = m.texcoords0[idx[k]];
    if (!m.texcoords1.empty()) c.uv[1][k] = m.texcoords1[idx[k]];
  }
  c.material = m.material;
  return c;
}

SurfaceHit TextureCorners::at(float u, float v) const {
  SurfaceHit s;
  for (int k = 0; k < 2; ++k) s.uv[k] = (1.0f - u - v) * uv[k][0] + u * uv[k][1] + v * uv[k][2];  // as interpolate()
  s.material = material;
  return s;
}

}  // namespace tessera
