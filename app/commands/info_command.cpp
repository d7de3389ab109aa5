// tessera info: what a glTF file holds, and what of it tessera supports.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "app/commands/commands.h"
#include "app/cli/exit_codes.h"
#include "app/frame/render_setup.h"
#include "scene_io/gltf_loader.h"

namespace tessera {

void add_info_command(CLI::App& app, InfoOptions& o) {
  CLI::App* cmd = app.add_subcommand("info", "Print what a glTF 2.0 scene holds: triangles, meshes, materials, "
                                             "textures, cameras, lights, bounds and extensions.");
  cmd->add_option("scene", o.scene_path, "The glTF file")->required();
  cmd->add_option("--scene", o.scene, "glTF scene by index or name [default: the file's default scene, else 0]");
  cmd->add_option("--fps", o.fps, "Frames per second for the animations' frame range")
      ->check(CLI::Range(1e-3, 1e6))->capture_default_str();
  cmd->add_flag("--json", o.json, "Print the same facts as one JSON document, for scripts (docs/usage.md lists its fields)");
}

namespace {

const char* const kLightTypes[] = {"point", "spot", "directional"};
const char* const kChannelPaths[] = {"translation", "rotation", "scale", "weights"};

std::string extension_list(const std::vector<std::string>& names) {
  if (names.empty()) return "none";
  std::string out = std::to_string(names.size());
  for (const std::string& n : names)
    out += fmt::format("\n  {} ({})", n, describe_extension_status(n));  // one per line: statuses are long
  return out;
}

// Each animation: its channels, key range and the frames that cover it at `fps` (render
// --frame N shows time N / fps; all animations play together by default).
void print_animations(const std::vector<Animation>& animations, double fps) {
  if (animations.empty()) return;
  float start = animations[0].start, end = animations[0].end;
  for (const Animation& a : animations) start = std::min(start, a.start), end = std::max(end, a.end);
  fmt::print("animations  {} (render --animation NAME or INDEX, --time S or --frame N), frames {}..{} at {:g} fps\n",
             animations.size(), static_cast<long long>(std::floor(start * fps)),
             static_cast<long long>(std::ceil(end * fps)), fps);
  for (std::size_t i = 0; i < animations.size(); ++i) {
    const Animation& a = animations[i];
    std::string paths;
    for (const char* p : kChannelPaths) {
      int n = 0;
      for (const AnimationChannel& c : a.channels) n += std::string(kChannelPaths[static_cast<int>(c.path)]) == p;
      if (n > 0) paths += fmt::format("{}{} {}", paths.empty() ? "" : ", ", n, p);
    }
    fmt::print("  {}: '{}' {} channel{} ({}), {:.4g}..{:.4g} s\n", i, a.name, a.channels.size(),
               a.channels.size() == 1 ? "" : "s", paths.empty() ? "none" : paths, a.start, a.end);
  }
}

// The numbers both the text and the JSON report.
struct SceneCounts {
  std::uint64_t unique = 0, placed = 0, primitives = 0;
  std::size_t textured = 0;
};

SceneCounts count_scene(const SceneDescription& s) {
  SceneCounts c;
  for (const Mesh& m : s.meshes) {
    c.primitives += m.primitives.size();
    for (const TriangleMesh& p : m.primitives) c.unique += p.triangle_count();
  }
  for (const Instance& inst : s.instances)
    for (const TriangleMesh& p : s.meshes[inst.mesh].primitives) c.placed += p.triangle_count();
  for (const Image& img : s.images) c.textured += img.pixels != nullptr;  // decoded: a used material shows it
  return c;
}

nlohmann::json vec_json(const glm::vec3& v) { return {v.x, v.y, v.z}; }

nlohmann::json extensions_json(const std::vector<std::string>& names) {
  nlohmann::json out = nlohmann::json::array();
  for (const std::string& n : names) out.push_back({{"name", n}, {"status", describe_extension_status(n)}});
  return out;
}

nlohmann::json animations_json(const std::vector<Animation>& animations, double fps) {
  nlohmann::json out = nlohmann::json::array();
  for (const Animation& a : animations) {
    nlohmann::json paths = nlohmann::json::object();
    for (const AnimationChannel& c : a.channels) {
      nlohmann::json& n = paths[kChannelPaths[static_cast<int>(c.path)]];
      n = n.is_null() ? 1 : n.get<int>() + 1;
    }
    out.push_back({{"name", a.name}, {"channels", a.channels.size()}, {"paths", paths}, {"start", a.start},
                   {"end", a.end}, {"first_frame", static_cast<long long>(std::floor(a.start * fps))},
                   {"last_frame", static_cast<long long>(std::ceil(a.end * fps))}});
  }
  return out;
}

nlohmann::json cameras_json(const std::vector<Camera>& cameras) {
  nlohmann::json out = nlohmann::json::array();
  for (const Camera& c : cameras) {
    if (c.projection == Camera::Projection::Perspective)
      out.push_back({{"name", c.name}, {"projection", "perspective"}, {"yfov_degrees", glm::degrees(c.yfov)},
                     {"aspect_ratio", c.aspect_ratio > 0 ? nlohmann::json(c.aspect_ratio) : nlohmann::json()}});
    else
      out.push_back({{"name", c.name}, {"projection", "orthographic"}, {"xmag", c.xmag}, {"ymag", c.ymag}});
  }
  return out;
}

// The facts `info` prints, as one JSON document; the indices are the arrays' (what --camera,
// --variant and --animation take).
void print_info_json(const InfoOptions& o, const GltfLoadResult& loaded) {
  const SceneDescription& s = loaded.scene;
  const SceneCounts c = count_scene(s);
  nlohmann::json lights = nlohmann::json::array();
  for (const PunctualLight& l : s.lights)
    lights.push_back({{"name", l.name}, {"type", kLightTypes[static_cast<int>(l.type)]}, {"intensity", l.intensity},
                      {"unit", l.type == PunctualLight::Type::Directional ? "lux" : "cd"}});
  nlohmann::json skins = nlohmann::json::array();
  for (const Skin& k : loaded.skins)
    skins.push_back({{"name", k.name}, {"joints", k.joints.size()},
                     {"skeleton", k.skeleton >= 0 ? nlohmann::json(k.skeleton) : nlohmann::json()}});
  const nlohmann::json doc = {
      {"file", o.scene_path},
      {"scene", s.scene_name.empty() ? nlohmann::json() : nlohmann::json(s.scene_name)},
      {"triangles", {{"unique", c.unique}, {"instanced", c.placed}}},
      {"meshes", {{"count", s.meshes.size()}, {"primitives", c.primitives}, {"placements", s.instances.size()}}},
      {"materials", s.materials.size()},
      {"variants", loaded.material_variants},
      {"animations", animations_json(loaded.animations, o.fps)},
      {"fps", o.fps},
      {"morph_meshes", loaded.morph_meshes},
      {"skins", skins},
      {"textures", c.textured},
      {"cameras", cameras_json(s.cameras)},
      {"lights", {{"punctual", lights}, {"emissive_triangles", emissive_triangle_count(s)}}},
      {"bounds", s.bounds.empty() ? nlohmann::json()
                                  : nlohmann::json{{"min", vec_json(s.bounds.lo)}, {"max", vec_json(s.bounds.hi)}}},
      {"extensions", {{"used", extensions_json(s.extensions_used)}, {"required", extensions_json(s.extensions_required)}}},
      {"warnings", loaded.warnings},
  };
  fmt::print("{}\n", doc.dump(2));
}

}  // namespace

int run_info(const InfoOptions& o) {
  GltfLoadResult loaded = load_gltf(o.scene_path, {o.scene});
  for (const std::string& w : loaded.warnings) fmt::print(stderr, "tessera: warning: {}: {}\n", o.scene_path, w);
  if (o.json) {
    print_info_json(o, loaded);
    return kExitSuccess;
  }
  const SceneDescription& s = loaded.scene;
  const SceneCounts counts = count_scene(s);

  fmt::print("file        {}\n", o.scene_path);
  fmt::print("scene       {}\n", s.scene_name.empty() ? "(all root nodes)" : s.scene_name);
  fmt::print("triangles   {} unique, {} instanced (as placed in the scene)\n", counts.unique, counts.placed);
  fmt::print("meshes      {} ({} primitives), placed {} times\n", s.meshes.size(), counts.primitives, s.instances.size());
  fmt::print("materials   {}\n", s.materials.size());
  if (!loaded.material_variants.empty()) {  // KHR_materials_variants: render --variant NAME|INDEX
    fmt::print("variants    {} (render --variant NAME or INDEX)\n", loaded.material_variants.size());
    for (std::size_t i = 0; i < loaded.material_variants.size(); ++i)
      fmt::print("  {}: '{}'\n", i, loaded.material_variants[i]);
  }
  print_animations(loaded.animations, o.fps);
  if (loaded.morph_meshes > 0) fmt::print("morphs      {} meshes with morph targets\n", loaded.morph_meshes);
  if (!loaded.skins.empty()) {
    fmt::print("skins       {}\n", loaded.skins.size());
    for (std::size_t i = 0; i < loaded.skins.size(); ++i) {
      const Skin& k = loaded.skins[i];
      fmt::print("  {}: '{}' {} joints{}\n", i, k.name, k.joints.size(),
                 k.skeleton >= 0 ? fmt::format(", skeleton node {}", k.skeleton) : "");
    }
  }
  fmt::print("textures    {} images shown (of {} in the file)\n", counts.textured, s.images.size());
  fmt::print("cameras     {}\n", s.cameras.size());
  for (std::size_t i = 0; i < s.cameras.size(); ++i) {
    const Camera& c = s.cameras[i];
    if (c.projection == Camera::Projection::Perspective)
      fmt::print("  {}: '{}' perspective, vertical fov {:.2f} deg{}\n", i, c.name, glm::degrees(c.yfov),
                 c.aspect_ratio > 0 ? fmt::format(", aspect {:.4g}", c.aspect_ratio) : "");
    else
      fmt::print("  {}: '{}' orthographic, xmag {:.4g}, ymag {:.4g}\n", i, c.name, c.xmag, c.ymag);
  }
  fmt::print("lights      {} punctual, {} emissive triangles\n", s.lights.size(), emissive_triangle_count(s));
  for (std::size_t i = 0; i < s.lights.size(); ++i)
    fmt::print("  {}: '{}' {}, intensity {:.4g} {}\n", i, s.lights[i].name, kLightTypes[static_cast<int>(s.lights[i].type)],
               s.lights[i].intensity, s.lights[i].type == PunctualLight::Type::Directional ? "lux" : "cd");
  if (s.bounds.empty())
    fmt::print("bounds      empty\n");
  else
    fmt::print("bounds      ({:.4g}, {:.4g}, {:.4g}) .. ({:.4g}, {:.4g}, {:.4g})\n", s.bounds.lo.x, s.bounds.lo.y,
               s.bounds.lo.z, s.bounds.hi.x, s.bounds.hi.y, s.bounds.hi.z);
  fmt::print("extensions  used: {}\n", extension_list(s.extensions_used));
  fmt::print("extensions  required: {}\n", extension_list(s.extensions_required));
  return kExitSuccess;
}

}  // namespace tessera
