#include "app/frame/frame_pipeline.h"

#include <algorithm>
#include <cmath>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>

#include <fmt/format.h>

#include "app/frame/auto_background.h"
#include "app/cli/camera_options.h"
#include "app/cli/exit_codes.h"
#include "app/frame/frame_denoise.h"
#include "app/frame/frame_sequence.h"
#include "app/frame/memory_check.h"
#include "app/profile/profile_outputs.h"
#include "app/frame/render_setup.h"
#include "app/cli/resume_options.h"
#include "renderer/sampling/adaptive_sampling.h"
#include "renderer/parallel/tile_scheduler.h"
#include "imageio/environment_image.h"

namespace tessera {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// A colour given as R,G,B or one number; "auto" is none (nullopt). Throws UsageError.
std::optional<vec3> background_color(const std::string& text) {
  if (text == "auto") return std::nullopt;
  vec3 c;
  char tail;
  const int n = std::sscanf(text.c_str(), "%f,%f,%f%c", &c.r, &c.g, &c.b, &tail);
  if (n == 1) c = vec3(c.r);
  else if (n != 3) throw UsageError("--background " + text + ": expected R,G,B (three numbers), one number, or auto");
  if (!is_finite(c) || glm::any(glm::lessThan(c, vec3(0.0f))))
    throw UsageError("--background " + text + ": values must be finite and not negative");
  return c;
}

// `described`: what the summary line says of it ("white (auto: no lights)").
vec3 parse_background(const std::string& text, const SceneDescription& scene, std::string& described) {
  if (const std::optional<vec3> c = background_color(text)) {
    described = text;
    return *c;
  }
  const AutoBackground choice = choose_auto_background(scene);
  described = fmt::format("{} (auto: {})", choice.black ? "black" : "white", choice.why);
  return vec3(choice.black ? 0.0f : 1.0f);
}

struct CropFractions {
  double x0, x1, y0, y1;
};

CropFractions crop_fractions(const std::string& text) {
  CropFractions f;
  char tail;
  if (std::sscanf(text.c_str(), "%lf,%lf,%lf,%lf%c", &f.x0, &f.x1, &f.y0, &f.y1, &tail) != 4 ||
      !(0.0 <= f.x0 && f.x0 < f.x1 && f.x1 <= 1.0) || !(0.0 <= f.y0 && f.y0 < f.y1 && f.y1 <= 1.0))
    throw UsageError("--crop " + text + ": expected X0,X1,Y0,Y1 with 0 <= X0 < X1 <= 1 and 0 <= Y0 < Y1 <= 1");
  return f;
}

// pbrt's rule: the crop [x0, x1) x [y0, y1) in fractions covers the pixels from ceil(x0 W)
// up to ceil(x1 W), so adjacent crops tile the frame without overlap.
Tile crop_region(const std::string& text, int width, int height) {
  const auto [x0, x1, y0, y1] = crop_fractions(text);
  auto at = [](double f, int size) { return static_cast<int>(std::ceil(f * size)); };
  const Tile region{at(x0, width), at(y0, height), at(x1, width), at(y1, height)};
  if (region.x1 <= region.x0 || region.y1 <= region.y0)
    throw UsageError(fmt::format("--crop {}: holds no pixel of the {}x{} frame", text, width, height));
  return region;
}

// Width, height and the camera: the chosen camera decides the aspect ratio before the size
// is known.
void plan_image(const RenderOptions& o, const SceneDescription& scene, const Bounds3* framing, FramePlan& plan) {
  RenderSettings& s = plan.settings;
  s.width = o.width;
  s.height = o.height;
  const Bounds3& bounds = framing ? *framing : scene.bounds;
  const std::optional<LookAt> look_at = command_line_look_at(o, bounds.empty() ? vec3(0.0f) : bounds.center());
  const std::optional<Orbit> orbit = command_line_orbit(o);
  const Camera* scene_camera = nullptr;
  Camera probe;
  if (!look_at && !orbit && (!scene.cameras.empty() || !o.camera.empty())) {
    probe = choose_camera(scene, o.camera, 16, 9, framing);
    scene_camera = &probe;
  }
  resolve_resolution(scene_camera, s.width, s.height);
  if (o.resolution_scale != 1.0f) {
    s.width = std::max(1, static_cast<int>(std::lround(s.width * static_cast<double>(o.resolution_scale))));
    s.height = std::max(1, static_cast<int>(std::lround(s.height * static_cast<double>(o.resolution_scale))));
  }
  if (static_cast<double>(s.width) * s.height > (1u << 28))
    throw UsageError(fmt::format("--width {} --height {}: more than 268 million pixels", s.width, s.height));
  if (look_at) plan.camera = look_at_camera(look_at->eye, look_at->target, look_at->up, s.width, s.height);
  else if (orbit) plan.camera = orbit_camera(bounds, orbit->azimuth, orbit->elevation, orbit->distance, s.width, s.height);
  else plan.camera = choose_camera(scene, o.camera, s.width, s.height, framing);
  plan.camera_params = {o.fov, o.aperture, o.focus_distance};
  if (!o.crop.empty()) {
    const Tile region = crop_region(o.crop, s.width, s.height);
    s.window = {region.x0, region.y0, s.width, s.height};
    s.width = region.x1 - region.x0;
    s.height = region.y1 - region.y0;
  }
}

void plan_sampling(const RenderOptions& o, RenderSettings& s) {
  s.spp = o.spp;
  s.max_bounces = o.max_bounces;
  s.threads = o.threads;
  s.tile_size = o.tile_size;
  s.light_sampling = o.light_sampling == "bsdf"     ? LightSampling::BsdfOnly
                     : o.light_sampling == "lights" ? LightSampling::LightsOnly
                                                    : LightSampling::Mis;
  s.light_tree = parse_light_tree_use(o.light_tree);
  s.guiding = parse_guiding_use(o.guiding);
  s.clamp = o.clamp;
  s.seed = static_cast<std::uint32_t>(o.seed);
  s.sampler = parse_sampler(o.sampler);
  s.filter = {parse_pixel_filter(o.pixel_filter), o.filter_width};
  s.adaptive = {o.noise_threshold, o.min_spp};
  if (o.min_spp > 0 && o.noise_threshold <= 0.0f) throw UsageError("--min-spp: needs --noise-threshold");
  s.scheduler = parse_scheduler(o.scheduler);
  s.tile_order = parse_tile_order(o.tile_order);
  s.record_tiles = ProfileOutputs{o.stats_json, o.trace, o.heatmap}.needs_tile_records();
  s.time_limit = o.time_limit;
}

bool same_environment(const EnvironmentParams& a, const EnvironmentParams& b) {
  return a.background == b.background && a.image_path == b.image_path && a.scale == b.scale &&
         a.rotate_degrees == b.rotate_degrees;
}

}  // namespace

void check_value_syntax(const RenderOptions& o) {
  background_color(o.background);
  if (!o.crop.empty()) crop_fractions(o.crop);
}

std::string frame_output_path(const RenderOptions& o) {
  if (!o.output.empty()) return o.output;
  if (!o.resume.empty()) return finished_sibling(o.resume);
  return std::filesystem::path(o.scene_path).stem().string() + ".exr";
}

float scene_time(const RenderOptions& o) {
  return static_cast<float>(o.frame >= 0 ? o.frame / o.fps : o.time);
}

Shutter parse_shutter(const RenderOptions& o) {
  if (o.shutter.empty()) return {};
  double open = 0.0, close = 0.0;
  char tail;
  if (std::sscanf(o.shutter.c_str(), "%lf,%lf%c", &open, &close, &tail) != 2 || !std::isfinite(open) ||
      !std::isfinite(close) || open > close || close - open > 1e6)
    throw UsageError("--shutter " + o.shutter + ": expected OPEN,CLOSE in frames with OPEN <= CLOSE, e.g. -0.25,0.25");
  return {static_cast<float>(open / o.fps), static_cast<float>(close / o.fps)};
}

LoadedScene load_scene(const RenderOptions& o, const GltfDocument& document, bool print_warnings) {
  const auto start = std::chrono::steady_clock::now();
  const Shutter shutter = parse_shutter(o);
  GltfLoadParams params{o.scene, o.variant, o.animation, scene_time(o)};
  if (shutter.on()) params.shutter_open = shutter.open, params.shutter_close = shutter.close, params.motion_steps = o.motion_steps;
  LoadedScene loaded{convert_gltf(document, params)};
  if (print_warnings)
    for (const std::string& w : loaded.gltf.warnings) fmt::print(stderr, "tessera: warning: {}: {}\n", o.scene_path, w);
  for (const Mesh& m : loaded.gltf.scene.meshes)
    for (const TriangleMesh& p : m.primitives) loaded.triangles += p.triangle_count();
  loaded.seconds = seconds_since(start);
  return loaded;
}

FramePlan plan_frame(const RenderOptions& o, const GltfLoadResult& loaded, const Bounds3* framing) {
  const SceneDescription& scene = loaded.scene;
  FramePlan plan;
  if (loaded.material_variant >= 0) {
    plan.material_variant = loaded.material_variant;
    plan.material_variant_name = loaded.material_variants[loaded.material_variant];
  }
  plan.animated = !loaded.playing.empty();
  plan.pose = fmt::format("{}\n{}\n{}\n{}\n{}\n{}\n{}", o.scene, o.variant, o.animation, scene_time(o), o.shutter, o.fps,
                          o.motion_steps);
  plan.output = frame_output_path(o);
  plan.preview = o.preview;
  plan.display = plan_display(o.display);
  plan_image(o, scene, framing, plan);
  plan_sampling(o, plan.settings);
  AovSelection& aovs = plan.settings.aovs;
  for (const std::string& a : o.aovs) {
    aovs.albedo |= a == "albedo";
    aovs.normal |= a == "normal";
    aovs.depth |= a == "depth";
    aovs.halves |= a == "halves";
  }
  plan.cost_layer = std::find(o.aovs.begin(), o.aovs.end(), "cost") != o.aovs.end();
  plan.denoise = o.denoise;
  if (o.denoise) aovs.albedo = aovs.normal = aovs.halves = true;  // what the denoiser reads
  aovs.coverage = o.film_transparent;
  plan.environment.background = parse_background(o.background, scene, plan.background);
  if (!o.envmap.empty()) plan.background = "envmap " + o.envmap;
  plan.environment.image_path = o.envmap;
  plan.environment.scale = o.envmap_scale;
  plan.environment.rotate_degrees = o.envmap_rotate;
  const RenderSettings& s = plan.settings;
  check_render_memory(estimate_render_memory(scene, s.width, s.height, s.aovs, o.envmap, s.adaptive.on()));
  return plan;
}

BuiltFrame build_frame(LoadedScene loaded, const FramePlan& plan, SceneCache* cache) {
  const auto start = std::chrono::steady_clock::now();
  BuiltFrame built;
  const bool cached = cache && cache->scene && same_environment(cache->environment, plan.environment);
  if (cached && cache->pose == plan.pose) {
    built.scene = cache->scene;  // nothing moved: the scene as it is
    built.updated = true;
  } else if (cached && cache->scene->update(loaded.gltf.scene)) {
    built.scene = cache->scene;
    built.updated = true;
    cache->pose = plan.pose;
  } else {
    if (cache) cache->scene.reset();  // its memory is free before the new scene takes its own
    EnvironmentParams environment = plan.environment;
    if (!environment.image_path.empty()) environment.image = read_environment_image(environment.image_path);
    built.scene = std::make_shared<RenderScene>(std::move(loaded.gltf.scene), environment);
    if (cache) *cache = {built.scene, environment, plan.pose};
  }
  built.seconds = seconds_since(start);
  const RenderSettings& s = plan.settings;
  const bool cropped = s.window.cropped();  // the camera sees the whole frame
  built.camera = built.scene->camera(plan.camera, cropped ? s.window.full_width : s.width,
                                     cropped ? s.window.full_height : s.height, plan.camera_params);
  if (plan.camera_params.aperture > 0.0f && plan.camera_params.focus_distance <= 0.0f)
    built.camera.focus_distance = autofocus_distance(*built.scene, built.camera);
  return built;
}

ImageWriteParams frame_write_params(const RenderOptions& o, const FramePlan& plan, const RenderCamera& camera,
                                    const RenderStats& stats, bool partial) {
  const RenderSettings& settings = plan.settings;
  ImageWriteParams write;
  write.half = o.half;
  write.display = plan.display;
  write.window = settings.window;
  write.exposure = o.display.exposure;
  FrameMetadata& meta = write.metadata;
  meta.render_seconds = stats.seconds;
  meta.seed = settings.seed;
  meta.sampler = sampler_name(settings.sampler);
  meta.pixel_filter = describe(settings.filter);
  meta.threads = stats.threads;
  meta.tile_size = settings.tile_size;
  meta.max_bounces = settings.max_bounces;
  meta.dropped_samples = stats.dropped_samples;
  // The camera at the frame's own time, where compositors expect it, also when the shutter
  // opens before the frame (the frame's fraction of the shutter, 0 without one).
  const Shutter shutter = parse_shutter(o);
  const float frame_in_shutter = shutter.on() ? std::clamp(-shutter.open / (shutter.close - shutter.open), 0.0f, 1.0f) : 0.0f;
  meta.world_to_camera = camera.world_to_camera(frame_in_shutter);
  meta.world_to_ndc = camera.world_to_ndc(frame_in_shutter);
  meta.scene_path = o.scene_path;
  meta.camera_name = plan.camera.name;
  meta.material_variant = plan.material_variant_name;
  meta.animated = plan.animated;
  meta.scene_time = scene_time(o);
  if (shutter.on()) {
    meta.shutter_open = meta.scene_time + shutter.open;
    meta.shutter_close = meta.scene_time + shutter.close;
  }
  if (o.frame >= 0) {
    meta.frame = o.frame;
    meta.frames_per_second = static_cast<float>(o.fps);
  }
  meta.film_transparent = o.film_transparent;
  meta.owner = o.owner;
  meta.comments = o.comments;
  meta.command_line = o.command_line;
  meta.partial = partial;
  write.resume_options = stored_options_text(o);
  meta.target_spp = settings.spp;
  if (settings.adaptive.on()) {
    meta.noise_threshold = settings.adaptive.threshold;
    meta.min_spp = adaptive_min_spp(settings.adaptive, settings.spp);
    meta.converged_pixels = stats.converged_pixels;
  }
  return write;
}

double denoise_planned_frame(const FramePlan& plan, FrameImage& image, FrameMetadata& metadata) {
  metadata.denoised = true;
  return denoise_frame(image, denoise_params(plan.settings.threads, sampler_name(plan.settings.sampler)));
}

double finish_frame(const FramePlan& plan, FrameImage& image, ImageWriteParams params, const FilmState& film,
                    const std::string& resume_text, bool denoise) {
  const double seconds = denoise ? denoise_planned_frame(plan, image, params.metadata) : 0.0;
  if (params.metadata.partial && is_exr_path(plan.output)) {
    params.resume_film = &film;
    params.resume_settings = resume_text;
  }
  write_image(plan.output, image, params);
  params.resume_film = nullptr;
  if (!plan.preview.empty()) write_image(plan.preview, image, params);
  return seconds;
}

}  // namespace tessera
