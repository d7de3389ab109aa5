// The renderer's own plain scene description: what a scene loader (scene_io) produces and
// what the renderer consumes. Plain data, no behaviour, no glTF and no Embree in sight.
// Units and conventions follow glTF 2.0: metres, right-handed, +Y up, cameras look down -Z.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <memory_resource>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace tessera {

template <glm::length_t N>
bool all_finite(const glm::vec<N, float>& v) {
  return !glm::any(glm::isnan(v)) && !glm::any(glm::isinf(v));
}

struct Bounds3 {
  glm::vec3 lo{std::numeric_limits<float>::infinity()};
  glm::vec3 hi{-std::numeric_limits<float>::infinity()};

  bool empty() const { return lo.x > hi.x; }
  void extend(const glm::vec3& p) { lo = glm::min(lo, p); hi = glm::max(hi, p); }
  void extend(const Bounds3& b) { lo = glm::min(lo, b.lo); hi = glm::max(hi, b.hi); }
  glm::vec3 center() const { return 0.5f * (lo + hi); }
  glm::vec3 diagonal() const { return hi - lo; }
  // How far from the origin it reaches (its largest |coordinate|) and its longest side: how
  // finely floats hold it (render_origin.h).
  float reach() const {
    const glm::vec3 r = glm::max(glm::abs(lo), glm::abs(hi));
    return std::max(r.x, std::max(r.y, r.z));
  }
  float longest_side() const {
    const glm::vec3 d = diagonal();
    return std::max(d.x, std::max(d.y, d.z));
  }
};

// Decoded image pixels as stored in the file: 8 or 16 bits per channel (normalized
// integers) or 32-bit float, row-major, top row first, 1 to 4 channels. The bytes are shared
// and read-only: a document's decoded image and every scene converted from it are one
// buffer (a 2048^2 texture is 16 MiB; copies cost page faults).
struct Image {
  std::string name;
  int width = 0, height = 0, channels = 0, bits_per_channel = 8;
  std::shared_ptr<const std::vector<std::uint8_t>> pixels;  // null for an image left undecoded
};

enum class WrapMode : std::uint8_t { Repeat, ClampToEdge, MirroredRepeat };
enum class FilterMode : std::uint8_t { Linear, Nearest };

struct TextureTransform {  // KHR_texture_transform; identity by default
  glm::vec2 offset{0.0f};
  float rotation = 0.0f;
  glm::vec2 scale{1.0f};
};

// A reference from a material slot to an image, with how to sample it.
struct TextureRef {
  int image = -1;  // index into SceneDescription::images; -1 = no texture
  int texcoord = 0;  // TEXCOORD_n set
  WrapMode wrap_s = WrapMode::Repeat, wrap_t = WrapMode::Repeat;
  FilterMode filter = FilterMode::Linear;
  TextureTransform transform;

  bool present() const { return image >= 0; }
};

enum class AlphaMode : std::uint8_t { Opaque, Mask, Blend };

// glTF 2.0 metallic-roughness material with the extensions tessera reads.
struct Material {
  std::string name;
  glm::vec4 base_color_factor{1.0f};
  TextureRef base_color_texture;  // sRGB encoded
  float metallic_factor = 1.0f, roughness_factor = 1.0f;
  TextureRef metallic_roughness_texture;  // B = metallic, G = roughness, linear
  TextureRef normal_texture;
  float normal_scale = 1.0f;
  glm::vec3 emissive_factor{0.0f};
  TextureRef emissive_texture;  // sRGB encoded
  float emissive_strength = 1.0f;  // KHR_materials_emissive_strength
  AlphaMode alpha_mode = AlphaMode::Opaque;
  float alpha_cutoff = 0.5f;
  bool double_sided = false;

  // KHR_materials_transmission (R channel), KHR_materials_ior
  float transmission_factor = 0.0f;
  TextureRef transmission_texture;
  float ior = 1.5f;
  // KHR_materials_volume: thickness 0 = thin-walled (light passes without refraction)
  float thickness_factor = 0.0f;
  TextureRef thickness_texture;  // G channel
  glm::vec3 attenuation_color{1.0f};
  float attenuation_distance = std::numeric_limits<float>::infinity();
  // KHR_materials_specular
  float specular_factor = 1.0f;
  TextureRef specular_texture;  // A channel
  glm::vec3 specular_color_factor{1.0f};
  TextureRef specular_color_texture;  // sRGB encoded
  // KHR_materials_clearcoat
  float clearcoat_factor = 0.0f;
  TextureRef clearcoat_texture;  // R channel
  float clearcoat_roughness_factor = 0.0f;
  TextureRef clearcoat_roughness_texture;  // G channel
  TextureRef clearcoat_normal_texture;  // the coat's own normal map (tangent space, linear)
  float clearcoat_normal_scale = 1.0f;
  // KHR_materials_diffuse_transmission: a Lambertian transmission in the diffuse base
  float diffuse_transmission_factor = 0.0f;
  TextureRef diffuse_transmission_texture;  // A channel
  glm::vec3 diffuse_transmission_color_factor{1.0f};
  TextureRef diffuse_transmission_color_texture;  // sRGB encoded
  // KHR_materials_anisotropy: the specular lobe stretched along a direction in the tangent
  // plane, rotated counter-clockwise from the tangent by `anisotropy_rotation` radians
  float anisotropy_strength = 0.0f;
  float anisotropy_rotation = 0.0f;
  TextureRef anisotropy_texture;  // RG = direction in tangent space ([0,1] to [-1,1]), B = strength
  // KHR_materials_iridescence: a thin dielectric film over the specular layer
  float iridescence_factor = 0.0f;
  TextureRef iridescence_texture;  // R channel
  float iridescence_ior = 1.3f;
  float iridescence_thickness_min = 100.0f, iridescence_thickness_max = 400.0f;  // nm
  TextureRef iridescence_thickness_texture;  // G: mix(min, max, G); without it the maximum
  // KHR_materials_dispersion: 20 / Abbe number of the volume's glass; 0 = none
  float dispersion = 0.0f;
  // KHR_materials_sheen
  glm::vec3 sheen_color_factor{0.0f};
  TextureRef sheen_color_texture;  // sRGB encoded
  float sheen_roughness_factor = 0.0f;
  TextureRef sheen_roughness_texture;  // A channel
  // KHR_materials_unlit: baseColor is shown as is, no light reaches it
  bool unlit = false;
};

// Every texture of a material, with the encoding it is read in (colours sRGB, data linear).
struct TextureSlot {
  const TextureRef* ref;
  bool srgb;
};
inline std::array<TextureSlot, 18> texture_slots(const Material& m) {
  return {{{&m.base_color_texture, true}, {&m.emissive_texture, true}, {&m.specular_color_texture, true},
           {&m.sheen_color_texture, true}, {&m.diffuse_transmission_color_texture, true},
           {&m.metallic_roughness_texture, false}, {&m.normal_texture, false}, {&m.transmission_texture, false},
           {&m.thickness_texture, false}, {&m.specular_texture, false}, {&m.clearcoat_texture, false},
           {&m.clearcoat_roughness_texture, false}, {&m.sheen_roughness_texture, false},
           {&m.clearcoat_normal_texture, false}, {&m.anisotropy_texture, false},
           {&m.diffuse_transmission_texture, false}, {&m.iridescence_texture, false},
           {&m.iridescence_thickness_texture, false}}};
}

// A vertex attribute or index array: on the heap as a std::vector's, except where the
// renderer lays its world-space copies out together (renderer/geometry/scene_geometry.h).
template <typename T>
using MeshArray = std::pmr::vector<T>;

// One triangle list with one material (a glTF mesh primitive after strip/fan conversion).
// Attribute arrays are either empty or have one entry per position.
struct TriangleMesh {
  MeshArray<glm::vec3> positions;
  MeshArray<glm::vec3> normals;
  MeshArray<glm::vec4> tangents;  // xyz tangent, w = bitangent sign
  MeshArray<glm::vec2> texcoords0, texcoords1;
  MeshArray<glm::vec4> colors;  // COLOR_0 as linear RGBA
  MeshArray<std::uint32_t> indices;  // three per triangle
  int material = -1;  // -1 = the glTF default material
  // A mesh that deforms while the shutter is open (a skin, animated morph weights): its
  // positions, normals and tangents at motion steps 1 .. motion_steps - 1 (step 0 is the
  // arrays above), each as long as `positions`; normals and tangents only when the mesh has
  // them. Empty: it keeps its shape.
  std::vector<MeshArray<glm::vec3>> motion_positions, motion_normals;
  std::vector<MeshArray<glm::vec4>> motion_tangents;

  std::size_t triangle_count() const { return indices.size() / 3; }
  bool deforms() const { return !motion_positions.empty(); }
};

// A glTF mesh: the primitives drawn together wherever a node places the mesh.
struct Mesh {
  std::string name;
  std::vector<TriangleMesh> primitives;
};

// A placement of a mesh in the world. A mesh placed several times is stored once.
struct Instance {
  int mesh = -1;
  glm::mat4 object_to_world{1.0f};
  std::string node_name;
  // A placement that moves while the shutter is open: object_to_world at motion steps
  // 1 .. motion_steps - 1 (step 0 is object_to_world). Empty: it stands still.
  std::vector<glm::mat4> motion;
};

struct Camera {
  enum class Projection : std::uint8_t { Perspective, Orthographic };
  std::string name;
  Projection projection = Projection::Perspective;
  glm::mat4 camera_to_world{1.0f};  // rigid: looks down -Z, +Y up
  float yfov = 0.6911f;  // perspective: vertical field of view, radians
  float aspect_ratio = 0.0f;  // 0 = not given: use the image's
  float xmag = 1.0f, ymag = 1.0f;  // orthographic half extents
  float znear = 0.0f, zfar = 0.0f;  // 0 = none
  // A camera that moves while the shutter is open: camera_to_world at motion steps
  // 1 .. motion_steps - 1 (step 0 is camera_to_world). Empty: it stands still.
  std::vector<glm::mat4> motion;
};

// KHR_lights_punctual, with the specification's photometric units.
struct PunctualLight {
  enum class Type : std::uint8_t { Point, Spot, Directional };
  std::string name;
  Type type = Type::Point;
  glm::vec3 color{1.0f};
  float intensity = 1.0f;  // candela (point, spot) or lux (directional)
  float range = 0.0f;  // 0 = infinite
  float inner_cone_angle = 0.0f, outer_cone_angle = 0.7853982f;
  glm::vec3 position{0.0f};
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  // the way the light shines, world space
  // A light that moves while the shutter is open: its node's world transform at motion step 0
  // and at steps 1 .. motion_steps - 1 (`motion`); the light is at the transform's origin and
  // shines along its -Z. Empty motion: it stands still (light_to_world is then unused).
  glm::mat4 light_to_world{1.0f};
  std::vector<glm::mat4> motion;
};

struct SceneDescription {
  std::string source_path;
  std::string scene_name;
  std::vector<Image> images;
  std::vector<Material> materials;
  std::vector<Mesh> meshes;
  std::vector<Instance> instances;
  std::vector<Camera> cameras;
  std::vector<PunctualLight> lights;
  std::vector<std::string> extensions_used, extensions_required;
  Bounds3 bounds;  // world-space bounds of every instance, at every motion step
  // Motion blur: the shutter is open from scene time shutter_open to shutter_close (seconds),
  // and what moves in that time is described at motion_steps evenly spaced times, step 0 at
  // the opening and the last at the closing. 1: no motion blur, everything at shutter_open.
  float shutter_open = 0.0f, shutter_close = 0.0f;
  int motion_steps = 1;
  // The scene changes with the scene time (an animation plays): the renderer builds it so
  // that the next frame's description can update it, rebuilding only what moved.
  bool animated = false;
};

}  // namespace tessera
