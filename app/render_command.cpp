// tessera render: glTF in, HDR OpenEXR (and an optional preview) out.
#include <algorithm>
#include <filesystem>

#include <fmt/format.h>

#include "app/commands.h"
#include "app/exit_codes.h"
#include "app/frame_pipeline.h"
#include "app/interrupt.h"
#include "app/profile_outputs.h"
#include "app/progress.h"
#include "app/resume_settings.h"
#include "renderer/image_output.h"
#include "renderer/render.h"
#include "renderer/resume_layers.h"

namespace tessera {

void add_render_command(CLI::App& app, RenderOptions& o) {
  CLI::App* cmd = app.add_subcommand("render", "Render a glTF 2.0 scene (.gltf or .glb) to an HDR OpenEXR frame.");
  cmd->add_option("scene", o.scene_path, "The glTF file to render")->required();
  cmd->add_option("-o,--output", o.output,
                  "Output image; .exr writes float RGBA with AOV layers and render metadata, other "
                  "extensions (.png .jpg .ppm .hdr .tif ...) go through OpenImageIO [default: SCENE_NAME.exr]");
  cmd->add_option("--preview", o.preview, "Also write a display-referred preview (sRGB, with --exposure), e.g. out.png");
  cmd->add_option("--width", o.width, "Image width in pixels [default: 960, or from --height and the camera's aspect ratio]")
      ->check(CLI::Range(1, 32768));
  cmd->add_option("--height", o.height, "Image height in pixels [default: from the width and the camera's aspect ratio]")
      ->check(CLI::Range(1, 32768));
  cmd->add_option("--spp", o.spp, "Samples per pixel")->check(CLI::Range(1, 1 << 24))->capture_default_str();
  cmd->add_option("--max-bounces", o.max_bounces, "Most scattering events per path (0: emitters and environment only)")
      ->check(CLI::Range(0, 1024))->capture_default_str();
  cmd->add_option("--threads", o.threads, "Render threads [default: all cores]")->check(CLI::Range(1, 1024));
  cmd->add_option("--tile-size", o.tile_size, "Tile edge in pixels")->check(CLI::Range(1, 4096))->capture_default_str();
  cmd->add_option("--scheduler", o.scheduler,
                  "Who renders which tile: tiles (TBB tasks, dynamic, work stealing), chunks (one block of rows "
                  "per thread, static), counter (threads take the next tile from one shared atomic counter), "
                  "interleaved (tile i to thread i mod n, static). Same image with each")
      ->check(CLI::IsMember(scheduler_names()))->capture_default_str();
  cmd->add_option("--tile-order", o.tile_order,
                  "Order tiles are handed out: scanline, spiral (from the image centre outwards), hilbert "
                  "(along a Hilbert curve). Same image with each")
      ->check(CLI::IsMember(tile_order_names()))->capture_default_str();
  cmd->add_option("--stats-json", o.stats_json,
                  "Write the load-balance statistics as JSON: every tile in every sample wave (thread, start, end, "
                  "samples, rays), every thread (busy, idle), the frame (wall time, efficiency, imbalance, tail)");
  cmd->add_option("--trace", o.trace,
                  "Write a Chrome trace-event timeline (FILE.json: one track per thread, one slice per tile) "
                  "for Perfetto (ui.perfetto.dev) or chrome://tracing");
  cmd->add_option("--heatmap", o.heatmap,
                  "Write the CPU time spent on each tile as a colour map with a legend (FILE.png)");
  cmd->add_option("--seed", o.seed, "Seed of every random number (same seed, same image, for any thread count)")
      ->check(CLI::Range(0LL, 2147483647LL))->capture_default_str();
  cmd->add_option("--sampler", o.sampler,
                  "Sample pattern: sobol (Owen-scrambled Sobol points, stratified in every 2D decision of a path: "
                  "less noise at the same spp), independent (white noise, for comparison). Same image for any "
                  "thread count with either")
      ->check(CLI::IsMember(sampler_names()))->capture_default_str();
  cmd->add_option("--pixel-filter", o.pixel_filter,
                  "Pixel reconstruction filter, importance-sampled: blackman-harris (Cycles' default: sharp, "
                  "little aliasing or edge noise), gaussian, box (each sample inside its own pixel)")
      ->check(CLI::IsMember(pixel_filter_names()))->capture_default_str();
  cmd->add_option("--filter-width", o.filter_width, "Pixel filter's whole width in pixels [default: box 1, others 1.5]")
      ->check(CLI::Range(0.5f, 8.0f));
  cmd->add_option("--camera", o.camera, "Camera by index or name [default: the scene's first, else an automatic camera framing the scene]");
  cmd->add_option("--scene", o.scene, "glTF scene by index or name [default: the file's default scene, else 0]");
  cmd->add_option("--variant", o.variant,
                  "Material variant (KHR_materials_variants) by name or index: each primitive that maps it "
                  "gets its mapped material, the others keep theirs [default: the file's default materials]");
  cmd->add_option("--animation", o.animation,
                  "Which glTF animations play: a name, an index, all, or none [default: all, together, as viewers play them]");
  auto* time = cmd->add_option("--time", o.time, "Scene time in seconds at which animated nodes are posed [default: 0]")
                   ->check(CLI::Range(-1e7, 1e7));
  cmd->add_option("--frame", o.frame, "Frame number: the scene time is FRAME / --fps")
      ->check(CLI::Range(0, 100000000))->excludes(time);
  cmd->add_option("--fps", o.fps, "Frames per second for --frame")->check(CLI::Range(1e-3, 1e6))->capture_default_str();
  cmd->add_option("--aperture", o.aperture, "Thin-lens aperture diameter in scene units (0: pinhole)")
      ->check(CLI::Range(0.0f, 1e6f))->capture_default_str();
  cmd->add_option("--focus-distance", o.focus_distance,
                  "Distance to the plane in focus [default: what the image centre sees]")
      ->check(CLI::Range(0.0f, 1e9f));
  cmd->add_option("--fov", o.fov, "Vertical field of view in degrees, overriding a perspective camera's")
      ->check(CLI::Range(0.01f, 179.0f));
  cmd->add_option("--background", o.background,
                  "Uniform background radiance: R,G,B, or one number for grey, or 'auto': black when the scene has lights "
                  "(punctual, or emissive without an emissive texture), else white 1,1,1. Ignored with --envmap")
      ->capture_default_str();
  cmd->add_option("--envmap", o.envmap, "Equirectangular environment image (.hdr, .exr, ...) lighting the scene");
  cmd->add_option("--envmap-scale", o.envmap_scale, "Multiplier on the environment image's radiance")
      ->check(CLI::Range(0.0f, 1e9f))->capture_default_str();
  cmd->add_option("--envmap-rotate", o.envmap_rotate, "Rotation of the environment about +Y, degrees")
      ->capture_default_str();
  cmd->add_option("--aov", o.aovs,
                  "Extra EXR layers: albedo (Albedo.RGB), normal (N.XYZ, world space), depth (Z), "
                  "cost (cost.time: CPU seconds spent on the pixel's tile), halves (even.RGB and odd.RGB: "
                  "the means of the even- and odd-numbered samples, also even/odd.Albedo.RGB and even/odd.N.XYZ "
                  "with albedo and normal; spp: each pixel's sample count)")
      ->delimiter(',')
      ->check(CLI::IsMember({"albedo", "normal", "depth", "cost", "halves"}));
  cmd->add_flag("--denoise", o.denoise,
                "Denoise the finished frame (feature-guided regression on the half buffers, albedo and normal, "
                "which it turns on): RGB is the denoised image, noisy.R/G/B the beauty as rendered; the preview "
                "shows the denoised one. Not applied to checkpoints or an interrupted frame");
  cmd->add_flag("--half", o.half, "Write 16-bit half floats to the EXR instead of 32-bit floats");
  cmd->add_option("--exposure", o.exposure, "Exposure in stops applied to non-EXR outputs (display formats: then sRGB encoded; .hdr/.tif/.pfm: linear)")
      ->check(CLI::Range(-64.0f, 64.0f))->capture_default_str();
  cmd->add_flag("-q,--quiet", o.quiet, "No progress and no summary (warnings and errors still print)");
  cmd->add_option("--time-limit", o.time_limit,
                  "Stop starting tiles after this many seconds of sampling (the first sample wave always finishes); "
                  "--spp is then the most a pixel gets. The frame is written, partial and resumable")
      ->check(CLI::Range(0.001, 1e9));
  cmd->add_option("--checkpoint", o.checkpoint,
                  "Rewrite the outputs (atomically) with what is done, between sample waves, at most every this "
                  "many seconds; an EXR checkpoint can be continued with --resume")
      ->check(CLI::Range(0.001, 1e9));
  cmd->add_option("--resume", o.resume,
                  "Continue a partial or checkpointed EXR written by tessera (same scene file and same options "
                  "affecting pixels, else refused); the result is the same bit for bit as an uninterrupted render "
                  "[-o default: this file]");
  cmd->add_option("--light-sampling", o.light_sampling,
                  "How emitters and the environment are found: mis (BSDF and light sampling combined), "
                  "bsdf or lights (one strategy alone: noisier, same mean; for verification)")
      ->check(CLI::IsMember({"mis", "bsdf", "lights"}))
      ->capture_default_str();
  cmd->add_option("--clamp", o.clamp,
                  "Clamp each sample's luminance to this value to tame fireflies (biased: darkens highlights; "
                  "0 = off)")
      ->check(CLI::Range(0.0f, 1e30f))
      ->capture_default_str();
  cmd->add_option("--noise-threshold", o.noise_threshold,
                  "Adaptive sampling, as Cycles' Noise Threshold: between sample waves a pixel whose estimated "
                  "relative error (from the means of its even- and odd-numbered samples) is below this stops, "
                  "unless a neighbour is still noisy; --spp is then the most. E.g. 0.01. Writes the spp layer "
                  "(0 = off)")
      ->check(CLI::Range(0.0f, 1e6f))
      ->capture_default_str();
  cmd->add_option("--min-spp", o.min_spp,
                  "Adaptive sampling: samples every pixel gets before it may stop [default: as Cycles, "
                  "max(4, ceil(16 / threshold^0.3)): 64 at 0.01]")
      ->check(CLI::Range(4, 1 << 24));
}

namespace {

// "62% of pixels converged": how much adaptive sampling saved, and where the counts ended.
void print_adaptive_summary(const RenderSettings& settings, const RenderResult& result) {
  const FilmState& film = result.film;
  std::uint64_t total = 0;
  std::uint32_t most = 0;
  for (std::uint32_t n : film.samples) {
    total += n;
    most = std::max(most, n);
  }
  const double pixels = static_cast<double>(film.pixel_count());
  fmt::print(stderr,
             "tessera: noise threshold {}, min spp {}: {:.0f}% of pixels converged; {:.1f} spp on average "
             "(fewest {}, most {}), {:.0f}% of the samples of {} spp everywhere\n",
             settings.adaptive.threshold, adaptive_min_spp(settings.adaptive, settings.spp),
             100.0 * result.stats.converged_pixels / pixels, total / pixels, result.image.samples_per_pixel, most,
             100.0 * total / (pixels * settings.spp), settings.spp);
}

void print_summary(const RenderOptions& o, const std::string& output, const RenderSettings& settings,
                   const RenderResult& result) {
  const RenderStats& s = result.stats;
  const int spp = result.image.samples_per_pixel;
  fmt::print(stderr,
             "tessera: {}x{}, {} spp, {} threads, tile {}: {:.3f} M samples/s, {:.3f} M rays/s; {} {}: "
             "efficiency {:.1f}%, imbalance {:.2f}{}\n",
             settings.width, settings.height, spp, s.threads, settings.tile_size, s.camera_samples / s.seconds * 1e-6,
             s.rays / s.seconds * 1e-6, scheduler_name(settings.scheduler), tile_order_name(settings.tile_order),
             100.0 * s.efficiency, s.imbalance,
             s.dropped_samples ? fmt::format(", {} non-finite samples dropped", s.dropped_samples) : "");
  if (settings.adaptive.on()) print_adaptive_summary(settings, result);
  std::string why;
  if (s.cancelled) why = fmt::format("interrupted at {} spp; ", spp);
  else if (s.time_limited) why = fmt::format("time limit reached at {} spp; ", spp);
  if (s.resumed_samples > 0) why = fmt::format("resumed {}; ", o.resume) + why;
  if (spp == 0)
    fmt::print(stderr, "tessera: interrupted before every pixel had a sample: {} not written\n", output);
  else
    fmt::print(stderr, "tessera: {}wrote {}{}\n", why, output, o.preview.empty() ? "" : " and " + o.preview);
}

}  // namespace

int run_render(const RenderOptions& o) {
  // Every path and the resume file first: a bad one costs nothing.
  check_output_path(frame_output_path(o));
  std::string resumed_settings;
  if (!o.resume.empty()) resumed_settings = read_resume_settings(o.resume);
  if (!o.preview.empty()) check_output_path(o.preview);
  const ProfileOutputs profile_outputs{o.stats_json, o.trace, o.heatmap};
  check_profile_outputs(profile_outputs);

  LoadedScene loaded = load_scene(o);
  FramePlan plan = plan_frame(o, loaded.gltf);
  const double load_seconds = loaded.seconds;
  const std::uint64_t triangles = loaded.triangles;
  const BuiltFrame built = build_frame(std::move(loaded), plan);
  RenderSettings& settings = plan.settings;

  const std::string resume_text = resume_settings(o, settings, built.camera, plan.environment,
                                                  plan.material_variant, plan.material_variant_name);
  FilmState resumed;
  if (!o.resume.empty()) {
    check_resume_settings(o.resume, resumed_settings, resume_text);
    const int min_spp = settings.adaptive.on() ? adaptive_min_spp(settings.adaptive, settings.spp) : 0;
    resumed = read_resume_film(o.resume, {settings.width, settings.height, settings.aovs, settings.spp, min_spp});
  }
  if (o.checkpoint > 0.0) {
    settings.checkpoint_interval = o.checkpoint;
    // A checkpoint that cannot be written (disk full) does not stop the render: the frame
    // is still in memory, and the final write reports the error if it persists.
    settings.on_checkpoint = [&](const Film& film, const RenderStats& stats) {
      try {
        RenderStats at_checkpoint = stats;
        at_checkpoint.converged_pixels = film.converged_pixels();
        FrameImage image = film.resolve();
        finish_frame(plan, image, frame_write_params(o, plan, built.camera, at_checkpoint, true), film.state(),
                     resume_text, false);
      } catch (const OutputError& e) {
        fmt::print(stderr, "tessera: warning: checkpoint not written: {}\n", e.what());
      }
    };
  }

  RenderMonitor monitor;
  InterruptHandler interrupts(monitor.cancel);  // stays installed while writing
  RenderResult result;
  {
    const std::uint64_t total = o.resume.empty()
                                    ? static_cast<std::uint64_t>(settings.width) * settings.height * settings.spp
                                    : samples_left(resumed, settings.spp);
    ProgressDisplay progress(monitor, {total, o.quiet, "", false, settings.adaptive.on()});
    result = render_frame(*built.scene, built.camera, settings, &monitor, o.resume.empty() ? nullptr : &resumed);
  }
  if (plan.cost_layer) result.image.cost = tile_cost_image(result.profile);
  write_profile_outputs(profile_outputs, result,
                        fmt::format("{}: {}, {}, {} threads", std::filesystem::path(o.scene_path).filename().string(),
                                    o.scheduler, o.tile_order, result.stats.threads));
  double denoise_seconds = 0.0;
  if (result.image.samples_per_pixel > 0) {
    const bool partial = samples_left(result.film, settings.spp) > 0;  // done: converged, or at --spp
    denoise_seconds = finish_frame(plan, result.image, frame_write_params(o, plan, built.camera, result.stats, partial),
                                   result.film, resume_text, plan.denoise && !result.stats.cancelled);
  }
  if (!o.quiet) {
    fmt::print(stderr, "tessera: {}: {} triangles; load {:.2f} s, BVH and textures {:.2f} s (BVH {:.2f} s), render {:.2f} s{}\n",
               o.scene_path, triangles, load_seconds, built.seconds, built.scene->bvh_build_seconds, result.stats.seconds,
               denoise_seconds > 0.0 ? fmt::format(", denoise {:.2f} s", denoise_seconds) : "");
    print_summary(o, plan.output, settings, result);
  }
  return interrupts.interrupted() ? kExitInterrupted : kExitSuccess;
}

}  // namespace tessera
