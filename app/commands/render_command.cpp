// tessera render: glTF in, HDR OpenEXR (and an optional preview) out.
#include <algorithm>
#include <chrono>
#include <filesystem>

#include <fmt/format.h>

#include "app/commands/commands.h"
#include "app/cli/exit_codes.h"
#include "app/frame/frame_pipeline.h"
#include "app/frame/frame_sequence.h"
#include "app/terminal/progress.h"
#include "app/commands/render_job.h"
#include "app/cli/command_line.h"
#include "app/commands/option_rules.h"
#include "app/commands/pixel_report.h"
#include "app/cli/resume_options.h"
#include "renderer/render/render.h"

namespace tessera {

void add_render_command(CLI::App& app, RenderOptions& o) {
  CLI::App* cmd = app.add_subcommand("render", "Render a glTF 2.0 scene (.gltf or .glb) to an HDR OpenEXR frame.");
  cmd->add_option("scene", o.scene_path, "The glTF file to render [with --resume: the one the resumed file stores]");
  cmd->add_option("-o,--output", o.output,
                  "Output image; .exr writes float RGBA with AOV layers and render metadata, other "
                  "extensions (.png .jpg .ppm .hdr .tif ...) go through OpenImageIO [default: SCENE_NAME.exr]")
      ->group("Output");
  cmd->add_option("--preview", o.preview, "Also write a display-referred preview (sRGB, with --exposure), e.g. out.png")
      ->group("Output");
  cmd->add_option("--width", o.width, "Image width in pixels [default: 960, or from --height and the camera's aspect ratio]")
      ->check(CLI::Range(1, 32768))
      ->group("Output");
  cmd->add_option("--height", o.height, "Image height in pixels [default: from the width and the camera's aspect ratio]")
      ->check(CLI::Range(1, 32768))
      ->group("Output");
  cmd->add_option("--resolution-scale", o.resolution_scale,
                  "Scale the width and height by this (0.5: half each way; after --width/--height or the default)")
      ->check(CLI::Range(0.001f, 100.0f))->capture_default_str()
      ->group("Output");
  cmd->add_option("--crop", o.crop,
                  "Render only this region of the frame, X0,X1,Y0,Y1 as fractions of its width and height "
                  "(as pbrt's --cropwindow; 0,0.5,0,1 is the left half): pixels ceil(X0 W) to ceil(X1 W) - 1, "
                  "the same values as in the whole frame; the EXR keeps the frame as its display window")
      ->group("Output");
  cmd->add_option("--aov", o.aovs,
                  "Extra EXR layers: albedo (Albedo.RGB), normal (N.XYZ, world space), depth (Z), "
                  "cost (cost.time: CPU seconds spent on the pixel's tile), halves (even.RGB and odd.RGB: "
                  "the means of the even- and odd-numbered samples, also even/odd.Albedo.RGB and even/odd.N.XYZ "
                  "with albedo and normal; variance.RGB: the variance of each pixel's mean; spp: each pixel's sample count)")
      ->delimiter(',')
      ->check(CLI::IsMember({"albedo", "normal", "depth", "cost", "halves"}))
      ->group("Output");
  cmd->add_flag("--half", o.half,
                "Write the EXR's colour channels (RGBA and colour layers) as 16-bit half floats; Z, N, "
                "counts and times stay 32-bit")
      ->group("Output");
  // EXR compositing conventions (docs/usage.md, "The EXR"): alpha, and who made the frame.
  cmd->add_flag("--film-transparent", o.film_transparent,
                "EXR alpha = the fraction of each pixel's camera samples that hit geometry, and no background "
                "in RGB (premultiplied, for comping over a plate); the background still lights the scene")
      ->group("Output");
  cmd->add_option("--owner", o.owner, "The EXR's standard owner attribute")
      ->group("Output");
  cmd->add_option("--comments", o.comments, "The EXR's standard comments attribute")
      ->group("Output");
  add_display_options(cmd, o.display, "Output");
  cmd->add_flag("-q,--quiet", o.quiet, "No progress and no summary (warnings and errors still print)")
      ->group("Output");
  cmd->add_option("--spp", o.spp, "Samples per pixel")->check(CLI::Range(1, 1 << 24))->capture_default_str()
      ->group("Sampling");
  cmd->add_flag("--quick", o.quick,
                "Preset for a fast look: --resolution-scale 0.25 --spp 4 --max-bounces 4 (each unless given)")
      ->group("Sampling");
  cmd->add_option("--pixel", o.pixel,
                  "Trace only pixel X,Y of the frame (0,0: top left) with --spp samples and print its paths on "
                  "stdout: each vertex (position, material, lobe sampled, pdf, throughput) and what it adds; the "
                  "first 4 samples in full, then the pixel's mean (what the full render gives it). Writes no image")
      ->group("Sampling");
  cmd->add_option("--max-bounces", o.max_bounces, "Most scattering events per path (0: emitters and environment only)")
      ->check(CLI::Range(0, 1024))->capture_default_str()
      ->group("Sampling");
  cmd->add_option("--seed", o.seed, "Seed of every random number (same seed, same image, for any thread count)")
      ->check(CLI::Range(0LL, 2147483647LL))->capture_default_str()
      ->group("Sampling");
  cmd->add_option("--sampler", o.sampler,
                  "Sample pattern: sobol (Owen-scrambled Sobol points, stratified in every 2D decision of a path: "
                  "less noise at the same spp), independent (white noise, for comparison). Same image for any "
                  "thread count with either")
      ->check(CLI::IsMember(sampler_names()))->capture_default_str()
      ->group("Sampling");
  cmd->add_option("--pixel-filter", o.pixel_filter,
                  "Pixel reconstruction filter, importance-sampled: blackman-harris (Cycles' default: sharp, "
                  "little aliasing or edge noise), gaussian, box (each sample inside its own pixel)")
      ->check(CLI::IsMember(pixel_filter_names()))->capture_default_str()
      ->group("Sampling");
  cmd->add_option("--filter-width", o.filter_width, "Pixel filter's whole width in pixels [default: box 1, others 1.5]")
      ->check(CLI::Range(0.5f, 8.0f))
      ->group("Sampling");
  cmd->add_option("--light-sampling", o.light_sampling,
                  "How emitters and the environment are found: mis (BSDF and light sampling combined), "
                  "bsdf or lights (one strategy alone: noisier, same mean; for verification)")
      ->check(CLI::IsMember({"mis", "bsdf", "lights"}))
      ->capture_default_str()
      ->group("Sampling");
  cmd->add_option("--light-tree", o.light_tree,
                  "Point and spot lights: on samples one per path vertex from a light tree (by power, distance "
                  "and orientation), off samples each; auto: the tree with more than 8 of them. Emissive "
                  "triangles: on chooses them by their light tree, off by power; auto: the tree where a pilot "
                  "finds it cuts the light samples' variance 2x. Same mean")
      ->check(CLI::IsMember(light_tree_use_names()))
      ->capture_default_str()
      ->group("Sampling");
  cmd->add_option("--guiding", o.guiding,
                  "Path guiding: on learns where light comes from in the first sample waves (a quarter of the "
                  "samples) and draws half of the diffuse directions from it; auto: off (no scene measured "
                  "faster to equal noise with it yet). Same mean")
      ->check(CLI::IsMember(guiding_use_names()))
      ->capture_default_str()
      ->group("Sampling");
  cmd->add_option("--clamp", o.clamp,
                  "Clamp each sample's luminance to this value to tame fireflies (biased: darkens highlights; "
                  "0 = off)")
      ->check(CLI::Range(0.0f, 1e30f))
      ->capture_default_str()
      ->group("Sampling");
  cmd->add_option("--noise-threshold", o.noise_threshold,
                  "Adaptive sampling, as Cycles' Noise Threshold: between sample waves a pixel whose estimated "
                  "relative error (from the means of its even- and odd-numbered samples) is below this stops, "
                  "unless a neighbour is still noisy; --spp is then the most. E.g. 0.01. Writes the spp layer "
                  "(0 = off)")
      ->check(CLI::Range(0.0f, 1e6f))
      ->capture_default_str()
      ->group("Sampling");
  cmd->add_option("--min-spp", o.min_spp,
                  "Adaptive sampling: samples every pixel gets before it may stop [default: as Cycles, "
                  "max(4, ceil(16 / threshold^0.3)): 64 at 0.01]")
      ->check(CLI::Range(4, 1 << 24))
      ->group("Sampling");
  cmd->add_flag("--denoise", o.denoise,
                "Denoise the finished frame (feature-guided regression on the half buffers, albedo and normal, "
                "which it turns on): RGB is the denoised image, noisy.R/G/B the beauty as rendered; the preview "
                "shows the denoised one. Not applied to checkpoints or an interrupted frame")
      ->group("Sampling");
  cmd->add_option("--camera", o.camera, "Camera by index or name [default: the scene's first, else an automatic camera framing the scene]")
      ->group("Scene and camera");
  cmd->add_option("--scene", o.scene, "glTF scene by index or name [default: the file's default scene, else 0]")
      ->group("Scene and camera");
  cmd->add_option("--variant", o.variant,
                  "Material variant (KHR_materials_variants) by name or index: each primitive that maps it "
                  "gets its mapped material, the others keep theirs [default: the file's default materials]")
      ->group("Scene and camera");
  auto* look_at = cmd->add_option("--look-at", o.look_at,
                                  "Camera from the command line: EYE,TARGET,UP as nine numbers, e.g. 0,1,5,0,1,0,0,1,0 "
                                  "(field of view: --fov, else a 50 mm lens on 36 mm film, as the automatic camera)")
                      ->excludes("--camera")
                      ->group("Scene and camera");
  auto* position = cmd->add_option("--camera-position", o.camera_position,
                                   "Camera from the command line at X,Y,Z looking at --camera-target (up: +Y)")
                       ->excludes("--camera")->excludes(look_at)
                       ->group("Scene and camera");
  cmd->add_option("--camera-target", o.camera_target,
                  "With --camera-position: the point X,Y,Z the camera looks at [default: the scene's centre]")
      ->excludes("--camera")->excludes(look_at)->needs(position)
      ->group("Scene and camera");
  cmd->add_option("--orbit", o.orbit,
                  "Camera circling the scene's centre: AZIMUTH,ELEVATION[,DISTANCE], degrees about +Y from +Z and "
                  "above the ground plane, e.g. 30,20 (0,0: the automatic camera's place; distance: the automatic "
                  "camera's, which frames the scene)")
      ->excludes("--camera")->excludes(look_at)->excludes(position)
      ->group("Scene and camera");
  cmd->add_option("--fov", o.fov, "Vertical field of view in degrees, overriding a perspective camera's")
      ->check(CLI::Range(0.01f, 179.0f))
      ->group("Scene and camera");
  cmd->add_option("--aperture", o.aperture, "Thin-lens aperture diameter in scene units (0: pinhole)")
      ->check(CLI::Range(0.0f, 1e6f))->capture_default_str()
      ->group("Scene and camera");
  cmd->add_option("--focus-distance", o.focus_distance,
                  "Distance to the plane in focus [default: what the image centre sees]")
      ->check(CLI::Range(0.0f, 1e9f))
      ->group("Scene and camera");
  cmd->add_option("--background", o.background,
                  "Uniform background radiance: R,G,B, or one number for grey, or 'auto': black when the scene's lights can "
                  "light it (punctual, or untextured emitters giving at least 1% of the power a white background would), "
                  "else white 1,1,1. Ignored with --envmap")
      ->capture_default_str()
      ->group("Lights");
  cmd->add_option("--envmap", o.envmap, "Equirectangular environment image (.hdr, .exr, ...) lighting the scene")
      ->group("Lights");
  cmd->add_option("--envmap-scale", o.envmap_scale, "Multiplier on the environment image's radiance")
      ->check(CLI::Range(0.0f, 1e9f))->capture_default_str()
      ->group("Lights");
  cmd->add_option("--envmap-rotate", o.envmap_rotate, "Rotation of the environment about +Y, degrees")
      ->capture_default_str()
      ->group("Lights");
  cmd->add_option("--animation", o.animation,
                  "Which glTF animations play: a name, an index, all, or none [default: all, together, as viewers play them]")
      ->group("Time and resume");
  auto* time = cmd->add_option("--time", o.time, "Scene time in seconds at which animated nodes are posed [default: 0]")
                   ->check(CLI::Range(-1e7, 1e7))
      ->group("Time and resume");
  auto* frame = cmd->add_option("--frame", o.frame, "Frame number: the scene time is FRAME / --fps (a # run in -o becomes it)")
                    ->check(CLI::Range(0, 100000000))->excludes(time)
      ->group("Time and resume");
  cmd->add_option("--frames", o.frames,
                  "Render frames FIRST to LAST (every STEP-th) as a sequence: -o's run of # becomes each frame's "
                  "number, zero-padded (shot.####.exr; without #, .#### goes before the extension); --preview and "
                  "the profile outputs are numbered alike. The file is read once; the automatic camera frames the "
                  "whole animation")
                     ->excludes(time)->excludes(frame)
      ->group("Time and resume");
  cmd->add_option("--fps", o.fps, "Frames per second for --frame, --frames and --shutter")
      ->check(CLI::Range(1e-3, 1e6))->capture_default_str()
      ->group("Time and resume");
  cmd->add_flag("--skip-existing", o.skip_existing,
                "With --frames (or --frame): a frame whose output exists is skipped, except a partial EXR "
                "(interrupted, time-limited), which is continued where it stopped. Rerun an interrupted "
                "sequence this way (render-farm friendly)")
      ->group("Time and resume");
  cmd->add_option("--shutter", o.shutter,
                  "Motion blur: the shutter is open from OPEN to CLOSE frames around the frame's time, e.g. "
                  "-0.25,0.25 (a 180-degree shutter); each sample sees the scene at a time in it [default: no blur]")
      ->group("Time and resume");
  cmd->add_option("--motion-steps", o.motion_steps,
                  "Motion blur: times across the shutter at which moving objects, deforming meshes and the camera "
                  "are described (Embree interpolates between them)")
      ->check(CLI::Range(2, 129))->capture_default_str()
      ->group("Time and resume");
  cmd->add_option("--time-limit", o.time_limit,
                  "Stop starting tiles after this many seconds of sampling (the first sample wave always finishes); "
                  "--spp is then the most a pixel gets. The frame is written, partial and resumable")
      ->check(CLI::Range(0.001, 1e9))
      ->group("Time and resume");
  cmd->add_option("--checkpoint", o.checkpoint,
                  "Rewrite the outputs (atomically) with what is done, between sample waves, at most every this "
                  "many seconds; an EXR checkpoint can be continued with --resume")
      ->check(CLI::Range(0.001, 1e9))
      ->group("Time and resume");
  cmd->add_option("--resume", o.resume,
                  "Continue a partial or checkpointed EXR written by tessera: alone, with the scene and options "
                  "the file stores; an option given that contradicts them is refused (--spp may raise the target). "
                  "The result is the same bit for bit as an uninterrupted render "
                  "[-o default: this file; NAME.exr for NAME.partial.exr]")
      ->group("Time and resume");
  cmd->add_option("--threads", o.threads, "Render threads [default: all cores]")->check(CLI::Range(1, 1024))
      ->group("Threads and profiling");
  cmd->add_option("--tile-size", o.tile_size, "Tile edge in pixels")->check(CLI::Range(1, 4096))->capture_default_str()
      ->group("Threads and profiling");
  cmd->add_option("--scheduler", o.scheduler,
                  "Who renders which tile: tiles (TBB tasks, dynamic, work stealing), chunks (one block of rows "
                  "per thread, static), counter (threads take the next tile from one shared atomic counter), "
                  "interleaved (tile i to thread i mod n, static). Same image with each")
      ->check(CLI::IsMember(scheduler_names()))->capture_default_str()
      ->group("Threads and profiling");
  cmd->add_option("--tile-order", o.tile_order,
                  "Order tiles are handed out: scanline, spiral (from the image centre outwards), hilbert "
                  "(along a Hilbert curve). Same image with each")
      ->check(CLI::IsMember(tile_order_names()))->capture_default_str()
      ->group("Threads and profiling");
  cmd->add_option("--rank-scheduler", o.rank_scheduler,
                  "Under mpirun: how each wave's tiles are shared by the ranks: dynamic (batches from one counter, "
                  "as the tiles are finished) or static (one block per rank, the paper's chunks)")
      ->check(CLI::IsMember({"dynamic", "static"}))
      ->capture_default_str()
      ->group("Threads and profiling");
  cmd->add_option("--rank-timeout", o.rank_timeout,
                  "Under mpirun: end the job (exit 1, naming the rank) when a rank has given no sign of life, or rank 0 "
                  "has not answered a request, for this many seconds while another waits for it, or an MPI call has "
                  "not returned for that long (a stopped or hung node; ranks other than 0 wait 5 s more for rank 0); "
                  "it must exceed the longest "
                  "a rank works without contacting rank 0: a batch of tiles, a static block, a wave of a whole "
                  "frame (0: wait forever)")
      ->check(CLI::Range(0.0, 1e9))
      ->capture_default_str()
      ->group("Threads and profiling");
  cmd->add_option("--stats-json", o.stats_json,
                  "Write the load-balance statistics as JSON: every tile in every sample wave (rank, thread, start, "
                  "end, samples, rays), every rank (busy, idle, communication) and thread (busy, idle), the frame "
                  "(wall time, efficiency, imbalance, tail); under mpirun, every rank's")
      ->group("Threads and profiling");
  cmd->add_option("--trace", o.trace,
                  "Write a Chrome trace-event timeline (FILE.json: one track per thread, one slice per tile; under "
                  "mpirun one process per rank) for Perfetto (ui.perfetto.dev) or chrome://tracing")
      ->group("Threads and profiling");
  cmd->add_option("--heatmap", o.heatmap,
                  "Write the CPU time spent on each tile as a colour map with pixel axes and a colour bar in ms or s "
                  "(FILE.png or any 8-bit image format; FILE.svg for a vector drawing)")
      ->group("Threads and profiling");
  cmd->add_option("--heatmap-by", o.heatmap_by,
                  "What the heat map's colours show: cost (CPU time per tile) or rank (under mpirun: the rank that "
                  "spent the most CPU time on the tile)")
      ->check(CLI::IsMember({"cost", "rank"}))
      ->capture_default_str()
      ->group("Threads and profiling");
  cmd->footer(
      "Examples:\n"
      "  tessera render scenes/cornell-box/cornell-box.gltf --width 640 --spp 32 --denoise -o cornell-box.png\n"
      "      a clean picture from few samples (the README's: 640x640, 32 spp, denoised)\n"
      "  tessera render model.glb --quick --look-at 3,2,3,0,0,0,0,1,0 -o look.png\n"
      "      a fast low-resolution look from a chosen point\n"
      "  tessera render shot.glb --frames 1:48 -o shot.####.exr --aov albedo,normal,depth --skip-existing\n"
      "      an animation as numbered EXRs with AOV layers; rerun to continue where it stopped\n");
  // --resume takes every option not given from the file: which ones were given.
  cmd->parse_complete_callback([cmd, &o] { o.given = given_options(*cmd); });
}

namespace {

// The frames to render, each with its own options: --frames, else the one frame asked for.
struct PlannedFrame {
  RenderOptions options;
  std::string label;
};

std::vector<PlannedFrame> plan_frames(const RenderOptions& o) {
  if (o.frames.empty()) {
    RenderOptions one = o;
    one.output = frame_output_path(o);
    if (o.frame >= 0 && has_frame_number(one.output)) one.output = numbered_path(one.output, o.frame);
    return {{one, ""}};
  }
  const std::vector<int> numbers = frame_numbers(parse_frame_range(o.frames));
  std::vector<PlannedFrame> frames;
  for (std::size_t i = 0; i < numbers.size(); ++i) {
    RenderOptions f = o;
    f.frame = numbers[i];
    f.output = numbered_path(frame_output_path(o), numbers[i]);
    if (!o.preview.empty()) f.preview = numbered_path(o.preview, numbers[i]);
    for (std::string* profile : {&f.stats_json, &f.trace, &f.heatmap})
      if (!profile->empty()) *profile = numbered_path(*profile, numbers[i]);
    frames.push_back({std::move(f), fmt::format("frame {} ({} of {})", numbers[i], i + 1, numbers.size())});
  }
  return frames;
}

}  // namespace

int run_render(const RenderOptions& options, RankGroup* ranks) {
  RenderOptions o = options.resume.empty() ? options : with_stored_options(options);
  const bool leader = !ranks || ranks->rank() == 0;
  o.quiet = o.quiet || !leader;  // rank 0 speaks for the ranks
  if (o.scene_path.empty()) throw UsageError("scene: the glTF file to render is required (or --resume FILE)");
  if (!o.frames.empty() && !o.resume.empty())
    throw UsageError("--resume: continues one frame; a sequence continues its interrupted frame with --skip-existing");
  apply_quick_preset(o);
  check_option_conflicts(o);
  check_value_syntax(o);
  if (leader)
    for (const std::string& w : ignored_option_warnings(o, ranks && ranks->size() > 1))
      fmt::print(stderr, "tessera: warning: {}\n", w);
  if (!o.pixel.empty()) {
    if (!leader) return kExitSuccess;  // one process traces the pixel
    return run_pixel_report(o, read_gltf(o.scene_path));
  }
  std::vector<PlannedFrame> frames = plan_frames(o);
  for (const PlannedFrame& f : frames) check_frame_files(f.options);  // a bad path costs nothing
  const GltfDocument document = read_gltf(o.scene_path);
  if (leader && document.model.animations.empty())
    for (const char* option : {"--time", "--frame", "--frames"})
      if (given(o, option))
        fmt::print(stderr, "tessera: warning: {}: {} has no animation, so every time shows the same scene\n", option,
                   o.scene_path);
  Bounds3 framing = animation_bounds(o, document);
  const auto start = std::chrono::steady_clock::now();
  int rendered = 0, skipped = 0;
  SceneCache scene_cache;  // what the frames share: textures, the environment, unmoved BVHs
  // Under MPI, with at least as many frames as ranks, whole frames go to the ranks (each
  // taken from the shared counter and rendered by its rank alone); else the ranks share the
  // tiles of every frame.
  const bool whole_frames = ranks && ranks->size() > 1 && frames.size() >= static_cast<std::size_t>(ranks->size());
  RankGroup* tile_ranks = whole_frames ? nullptr : ranks;
  if (whole_frames) ranks->start_wave(frames.size());
  std::size_t sequential = 0;
  auto next_frame = [&] { return whole_frames ? ranks->next_items(1).first : sequential++; };  // frames.size(): none
  bool interrupted = false;
  for (std::size_t k = next_frame(); k < frames.size() && !interrupted; k = next_frame()) {
    PlannedFrame& f = frames[k];
    if (o.skip_existing) {
      const ExistingFrame existing = existing_frame(f.options.output);
      if (existing == ExistingFrame::Finished) {
        if (!o.quiet)
          fmt::print(stderr, "tessera: {}{} exists, skipped\n", f.label.empty() ? "" : f.label + ": ", f.options.output);
        ++skipped;
        continue;
      }
      if (existing == ExistingFrame::Partial) f.options.resume = f.options.output;
    }
    const bool first = rendered == 0;
    const FrameJobResult done = render_frame_job(
        f.options, {&document, framing.empty() ? nullptr : &framing, f.label, first, &scene_cache, tile_ranks,
                                 whole_frames ? ranks : nullptr});
    ++rendered;
    interrupted = done.interrupted;
  }
  if (whole_frames) {  // every rank gets here, interrupted or not: the sums are collective
    rendered = static_cast<int>(ranks->sum(rendered));
    skipped = static_cast<int>(ranks->sum(skipped));
  }
  if (interrupted) return kExitInterrupted;
  if (!o.quiet && !o.frames.empty())
    fmt::print(stderr, "tessera: frames {}: {} rendered{}, {} skipped, {}\n", o.frames, rendered,
               whole_frames ? fmt::format(" by {} ranks", ranks->size()) : "", skipped,
               format_duration(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()));
  return kExitSuccess;
}

}  // namespace tessera
