#include "app/commands/resume_settings.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <tuple>
#include <fstream>
#include <sstream>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "app/cli/exit_codes.h"
#include "app/frame/frame_pipeline.h"
#include "imageio/resume_layers.h"

namespace tessera {

namespace {

// fmt's {} prints the shortest text that reads back as the same float: exact and stable.
std::string floats(const float* v, int n) {
  std::string s;
  for (int i = 0; i < n; ++i) s += (i ? "," : "") + fmt::format("{}", v[i]);
  return s;
}

std::string camera_lines(const RenderCamera& c) {
  const float scalars[] = {c.tan_half_fov_y, c.half_height, c.aspect, c.lens_radius, c.focus_distance, c.znear, c.zfar};
  return fmt::format("camera-projection={}\ncamera-to-world={}\ncamera-lens={}\n",
                     c.projection == Camera::Projection::Perspective ? "perspective" : "orthographic",
                     floats(&c.camera_to_world[0][0], 16), floats(scalars, 7));
}

std::vector<std::pair<std::string, std::string>> parse_lines(const std::string& text) {
  std::vector<std::pair<std::string, std::string>> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    const std::size_t eq = line.find('=');
    if (eq != std::string::npos) out.emplace_back(line.substr(0, eq), line.substr(eq + 1));
  }
  return out;
}

}  // namespace

std::string hash_file(const std::string& path) {
  // A frame sequence fingerprints the same files for every frame: once per file, size and
  // modification time is enough.
  static std::map<std::tuple<std::string, std::uintmax_t, std::filesystem::file_time_type>, std::string> known;
  std::error_code size_error, time_error;
  const auto key = std::make_tuple(path, std::filesystem::file_size(path, size_error),
                                   std::filesystem::last_write_time(path, time_error));
  const bool keyed = !size_error && !time_error;
  if (keyed)
    if (auto it = known.find(key); it != known.end()) return it->second;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw UsageError(path + ": cannot be read to fingerprint it");
  std::ostringstream bytes;
  bytes << in.rdbuf();
  std::string hash = fnv1a_hex(bytes.str());
  if (keyed) known[key] = hash;
  return hash;
}

std::string resume_settings(const RenderOptions& o, const RenderSettings& s, const RenderCamera& camera,
                            const EnvironmentParams& env, int variant, const std::string& variant_name) {
  std::string aovs;
  if (s.aovs.albedo) aovs += "albedo,";
  if (s.aovs.normal) aovs += "normal,";
  if (s.aovs.depth) aovs += "depth,";
  if (s.aovs.halves) aovs += "halves,";
  if (s.aovs.coverage) aovs += "film-transparent,";
  if (!aovs.empty()) aovs.pop_back();
  std::string text = fmt::format("format=1\nscene-bytes={}\nscene={}\n", hash_file(o.scene_path), o.scene);
  text += fmt::format("width={}\nheight={}\nspp={}\nmax-bounces={}\nseed={}\nsampler={}\n", s.width, s.height,
                      s.spp, s.max_bounces, s.seed, sampler_name(s.sampler));
  text += camera_lines(camera);
  text += fmt::format("background={}\n", floats(&env.background.r, 3));
  text += fmt::format("envmap-bytes={}\nenvmap-scale={}\nenvmap-rotate={}\n",
                      env.image_path.empty() ? "none" : hash_file(env.image_path), env.scale, env.rotate_degrees);
  text += fmt::format("aovs={}\n", aovs.empty() ? "none" : aovs);
  // Each only when it differs from what frames before it had (box pixels, MIS, no clamp), so
  // those still resume; the check compares both ways, so a change is never missed.
  if (describe(s.filter) != "box 1") text += fmt::format("pixel-filter={}\n", describe(s.filter));
  if (s.light_sampling != LightSampling::Mis)
    text += fmt::format("light-sampling={}\n", s.light_sampling == LightSampling::BsdfOnly ? "bsdf" : "lights");
  if (s.light_tree != LightTreeUse::Auto)  // auto decides from the scene, whose bytes are checked
    text += fmt::format("light-tree={}\n", light_tree_use_names()[static_cast<int>(s.light_tree)]);
  if (s.guiding != GuidingUse::Auto)
    text += fmt::format("guiding={}\n", guiding_use_names()[static_cast<int>(s.guiding)]);
  if (s.clamp > 0.0f) text += fmt::format("clamp={}\n", s.clamp);
  // Only with --variant (frames before it had the default materials): the index decides, the
  // name is for the message.
  if (variant >= 0) text += fmt::format("variant={} '{}'\n", variant, variant_name);
  // The pose: only when it differs from what frames had before animations (all at time 0).
  if (!o.animation.empty() && o.animation != "all") text += fmt::format("animation={}\n", o.animation);
  if (scene_time(o) != 0.0f) text += fmt::format("time={}\n", scene_time(o));
  if (const Shutter shutter = parse_shutter(o); shutter.on())
    text += fmt::format("shutter={},{}\nmotion-steps={}\n", shutter.open, shutter.close, o.motion_steps);
  // Only with adaptive sampling, so frames from before it still resume; the check below
  // compares both ways, so neither side can drop these lines unnoticed.
  if (s.adaptive.on())
    text += fmt::format("noise-threshold={}\nmin-spp={}\n", s.adaptive.threshold, adaptive_min_spp(s.adaptive, s.spp));
  if (s.window.cropped())  // the region of which frame
    text += fmt::format("crop={},{},{}x{}\n", s.window.x, s.window.y, s.window.full_width, s.window.full_height);
  return text;
}

namespace {

// A line is left out when its setting is what frames had before the line existed.
const std::pair<const char*, const char*> kUnwrittenDefaults[] = {
    {"pixel-filter", "box 1"}, {"light-sampling", "mis"}, {"light-tree", "auto"}, {"clamp", "0"}, {"animation", "all"}, {"time", "0"},
    {"shutter", "none"}, {"motion-steps", "1"}, {"crop", "none"}};

std::string value_of(const std::vector<std::pair<std::string, std::string>>& lines, const std::string& key) {
  for (const auto& [k, v] : lines)
    if (k == key) return v;
  for (const auto& [k, v] : kUnwrittenDefaults)
    if (key == k) return v;
  return "(nothing)";
}

// --spp may raise a fixed-count render's target: its samples are the first ones of the longer
// render's. An adaptive render's convergence checks ran at the old target's waves.
bool raises_spp(const std::vector<std::pair<std::string, std::string>>& then, const std::string& was,
                const std::string& now) {
  return std::stoll(now) > std::stoll(was) && value_of(then, "noise-threshold") == "(nothing)";
}

}  // namespace

int stored_spp(const std::string& stored) {
  const std::string spp = value_of(parse_lines(stored), "spp");
  return spp == "(nothing)" ? 0 : std::stoi(spp);
}

void check_resume_settings(const std::string& path, const std::string& stored, const std::string& current) {
  const auto then = parse_lines(stored), now_lines = parse_lines(current);
  auto keys = now_lines;  // this render's settings, then any the file has that it lacks
  for (const auto& line : then) {
    const bool listed = std::any_of(keys.begin(), keys.end(), [&](const auto& k) { return k.first == line.first; });
    if (!listed) keys.push_back(line);
  }
  for (const auto& line : keys) {
    const std::string& key = line.first;
    const std::string was = value_of(then, key), now = value_of(now_lines, key);
    if (was == now) continue;
    if (key == "spp" && raises_spp(then, was, now)) continue;
    if (key == "scene-bytes")
      throw UsageError(fmt::format("--resume {}: was rendered from another scene file (its bytes hash to {}, this "
                                   "scene's to {})", path, was, now));
    throw UsageError(fmt::format("--resume {}: {} differs: the file has {}, this render {}; resume with the "
                                 "options it was started with", path, key, was, now));
  }
}

}  // namespace tessera
