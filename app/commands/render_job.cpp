#include "app/commands/render_job.h"

#include <algorithm>
#include <filesystem>

#include <fmt/format.h>

#include "app/cli/exit_codes.h"
#include "app/frame/frame_pipeline.h"
#include "app/frame/frame_sequence.h"
#include "app/terminal/interrupt.h"
#include "app/profile/profile_outputs.h"
#include "app/terminal/progress.h"
#include "app/terminal/terminal.h"
#include "app/commands/resume_settings.h"
#include "imageio/image_output.h"
#include "renderer/render/render.h"
#include "imageio/resume_layers.h"

namespace tessera {

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
  print_status(fmt::format(
      "tessera: noise threshold {}, min spp {}: {:.0f}% of pixels converged; {:.1f} spp on average "
      "(fewest {}, most {}), {:.0f}% of the samples of {} spp everywhere",
      settings.adaptive.threshold, adaptive_min_spp(settings.adaptive, settings.spp),
      100.0 * result.stats.converged_pixels / pixels, total / pixels, result.image.samples_per_pixel, most,
      100.0 * total / (pixels * settings.spp), settings.spp));
}

// A distributed render: the cluster's efficiency and each rank's time (the extremes only for
// many ranks: --stats-json has them all).
void print_rank_summary(const FrameProfile& p) {
  constexpr std::size_t kListed = 8;
  auto describe = [](const RankStats& r) {
    return fmt::format("rank {} busy {:.3f} s, idle {:.3f} s, communication {:.3f} s ({:.1f}%)", r.rank, r.busy, r.idle,
                       r.communication, 100.0 * r.efficiency);
  };
  std::vector<RankStats> shown = p.ranks;
  if (shown.size() > kListed) {
    auto [least, most] = std::minmax_element(shown.begin(), shown.end(),
                                             [](const RankStats& a, const RankStats& b) { return a.efficiency < b.efficiency; });
    shown = {*least, *most};
  }
  std::string list;
  for (const RankStats& r : shown) list += "; " + describe(r);
  print_status(fmt::format("tessera: {} ranks: cluster efficiency {:.1f}% (busy / (threads x wall), wall {:.3f} s){}{}",
                           p.ranks.size(), 100.0 * p.balance.efficiency, p.balance.wall,
                           p.ranks.size() > kListed ? "; least and most efficient: " : "",
                           p.ranks.size() > kListed ? list.substr(2) : list));
}

void print_summary(const RenderOptions& o, const FramePlan& to, const RenderSettings& settings,
                   const RenderResult& result) {
  const std::string& output = to.output;
  const RenderStats& s = result.stats;
  const int spp = result.image.samples_per_pixel;
  print_status(fmt::format(
      "tessera: {}x{}, {} spp, {}{} threads, tile {}: {:.3f} M samples/s, {:.3f} M rays/s; {} {}: "
      "efficiency {:.1f}%, imbalance {:.2f}{}",
      settings.width, settings.height, spp, s.ranks > 1 ? fmt::format("{} ranks x ", s.ranks) : "", s.threads,
      settings.tile_size, s.camera_samples / s.seconds * 1e-6, s.rays / s.seconds * 1e-6,
      scheduler_name(settings.scheduler), tile_order_name(settings.tile_order), 100.0 * s.efficiency, s.imbalance,
      s.dropped_samples ? fmt::format(", {} non-finite samples dropped", s.dropped_samples) : ""));
  if (s.emitter_pick < 1.0f)
    print_status(fmt::format("tessera: emitters light-sampled at {:.0f}% of path vertices (their share of the direct "
                             "light the camera sees: docs/materials-and-lights.md#emitter-sampling)",
                             100.0 * s.emitter_pick));
  if (s.light_tree_lights > 0)
    print_status(fmt::format("tessera: one of {} point and spot lights sampled per path vertex by the light tree "
                             "(docs/materials-and-lights.md#many-lights)",
                             s.light_tree_lights));
  if (s.guide_rounds > 0)
    print_status(fmt::format("tessera: paths guided by what {} sample waves learnt, in {} regions of space "
                             "(docs/materials-and-lights.md#path-guiding)",
                             s.guide_rounds, s.guide_regions));
  if (s.emitter_tree_triangles > 0)
    print_status(fmt::format("tessera: emissive triangles chosen by the light tree, from {} of them, at each path "
                             "vertex (docs/materials-and-lights.md#many-lights)",
                             s.emitter_tree_triangles));
  if (!result.profile.ranks.empty()) print_rank_summary(result.profile);
  if (settings.adaptive.on()) print_adaptive_summary(settings, result);
  std::string why;
  if (s.cancelled) why = fmt::format("interrupted at {} spp; ", spp);
  else if (s.time_limited) why = fmt::format("time limit reached at {} spp; ", spp);
  if (s.resumed_samples > 0) why = fmt::format("resumed {}; ", o.resume) + why;
  if (spp == 0)
    print_status(fmt::format("tessera: interrupted before every pixel had a sample: {} not written", output));
  else
    print_status(fmt::format("tessera: {}wrote {}{}", why, output, to.preview.empty() ? "" : " and " + to.preview));
}

// Where a partial frame goes (a checkpoint; stopped by a signal or the time limit): -o,
// unless that holds a finished frame, which it never replaces; then NAME.partial.EXT beside
// it, and the preview alike.
FramePlan keeping_finished_frame(const FramePlan& plan) {
  if (existing_frame(plan.output) != ExistingFrame::Finished) return plan;
  FramePlan beside = plan;
  beside.output = partial_sibling(plan.output);
  if (!plan.preview.empty()) beside.preview = partial_sibling(plan.preview);
  return beside;
}

// A finished frame supersedes the partial one a signal or checkpoint left beside it.
void remove_superseded_partial(const std::string& output, bool quiet) {
  const std::string partial = partial_sibling(output);
  if (existing_frame(partial) != ExistingFrame::Partial) return;
  std::error_code ec;
  if (std::filesystem::remove(partial, ec) && !quiet) print_status(fmt::format("tessera: removed {}, now finished", partial));
}

}  // namespace

std::string check_frame_files(const RenderOptions& o) {
  check_output_path(frame_output_path(o));
  std::string resumed_settings;
  if (!o.resume.empty()) resumed_settings = read_resume_settings(o.resume);
  if (!o.preview.empty()) check_output_path(o.preview);
  check_profile_outputs({o.stats_json, o.trace, o.heatmap});
  return resumed_settings;
}

FrameJobResult render_frame_job(const RenderOptions& options, const FrameJob& job) {
  // Of the ranks of a distributed render, rank 0 alone speaks and writes.
  const bool leader = !job.ranks || job.ranks->rank() == 0;
  RenderOptions o = options;
  o.quiet = o.quiet || !leader;
  const std::string resumed_settings = check_frame_files(o);
  const ProfileOutputs profile_outputs{o.stats_json, o.trace, o.heatmap,
                                       o.heatmap_by == "rank" ? HeatmapBy::rank : HeatmapBy::cost};

  LoadedScene loaded = load_scene(o, *job.document, job.print_warnings && leader);
  FramePlan plan = plan_frame(o, loaded.gltf, job.framing);
  // The file is read once for a whole sequence: its first frame counts the reading.
  const double load_seconds = loaded.seconds + (job.print_warnings ? job.document->read_seconds : 0.0);
  const std::uint64_t triangles = loaded.triangles;
  const BuiltFrame built = build_frame(std::move(loaded), plan, job.scene_cache);
  RenderSettings& settings = plan.settings;

  const std::string resume_text = resume_settings(o, settings, built.camera, plan.environment,
                                                  plan.material_variant, plan.material_variant_name);
  FilmState resumed;
  if (!o.resume.empty()) {
    check_resume_settings(o.resume, resumed_settings, resume_text);
    const int min_spp = settings.adaptive.on() ? adaptive_min_spp(settings.adaptive, settings.spp) : 0;
    resumed = read_resume_film(o.resume, {settings.width, settings.height, settings.aovs, settings.spp, min_spp,
                                          settings.window, stored_spp(resumed_settings)});
  }
  settings.ranks = job.ranks;
  settings.alive_in = job.alive_in;
  settings.rank_scheduler = o.rank_scheduler == "static" ? RankScheduler::stat : RankScheduler::dynamic;
  if (o.checkpoint > 0.0 && leader) {
    settings.checkpoint_interval = o.checkpoint;
    // A checkpoint that cannot be written (disk full) does not stop the render: the frame
    // is still in memory, and the final write reports the error if it persists.
    settings.on_checkpoint = [&](const Film& film, const RenderStats& stats) {
      try {
        RenderStats at_checkpoint = stats;
        at_checkpoint.converged_pixels = film.converged_pixels();
        FrameImage image = film.resolve();
        const FramePlan to = keeping_finished_frame(plan);
        finish_frame(to, image, frame_write_params(o, to, built.camera, at_checkpoint, true), film.state(),
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
    ProgressDisplay progress(monitor, {total, o.quiet, job.label.empty() ? "" : job.label + ": ", false,
                                       settings.adaptive.on()});
    result = render_frame(*built.scene, built.camera, settings, &monitor, o.resume.empty() ? nullptr : &resumed);
  }
  if (!leader) return {interrupts.interrupted()};
  if (plan.cost_layer) result.image.cost = tile_cost_image(result.profile);
  write_profile_outputs(profile_outputs, result,
                        fmt::format("{}: {}, {}, {}{} threads", std::filesystem::path(o.scene_path).filename().string(),
                                    o.scheduler, o.tile_order,
                                    result.stats.ranks > 1 ? fmt::format("{} ranks x ", result.stats.ranks) : "",
                                    result.stats.threads));
  double denoise_seconds = 0.0;
  const bool partial = samples_left(result.film, settings.spp) > 0;  // done: converged, or at --spp
  const FramePlan to = partial ? keeping_finished_frame(plan) : plan;
  if (result.image.samples_per_pixel > 0) {
    denoise_seconds = finish_frame(to, result.image, frame_write_params(o, to, built.camera, result.stats, partial),
                                   result.film, resume_text, plan.denoise && !result.stats.cancelled);
    if (!partial) remove_superseded_partial(to.output, o.quiet);
  }
  if (!o.quiet) {
    const std::string build =
        built.updated ? fmt::format("scene updated in {:.2f} s ({} triangles rebuilt, textures kept)", built.seconds,
                                    built.scene->rebuilt_triangles)
                      : fmt::format("BVH and textures {:.2f} s (BVH {:.2f} s)", built.seconds, built.scene->bvh_build_seconds);
    print_status(fmt::format("tessera: {}: {} triangles; load {:.2f} s, {}, render {:.2f} s{}; background {}", o.scene_path,
                             triangles, load_seconds, build, result.stats.seconds,
                             denoise_seconds > 0.0 ? fmt::format(", denoise {:.2f} s", denoise_seconds) : "",
                             plan.background));
    if (to.output != plan.output && result.image.samples_per_pixel > 0)
      print_status(fmt::format("tessera: {} holds a finished frame, kept; the partial frame goes beside it (continue "
                               "it with --resume {})", plan.output, to.output));
    print_summary(o, to, settings, result);
  }
  return {interrupts.interrupted()};
}

Bounds3 animation_bounds(const RenderOptions& o, const GltfDocument& document) {
  Bounds3 bounds;
  // A camera of the file's, or nothing that plays: nothing to frame (and no conversion made).
  if (!o.camera.empty() || !o.look_at.empty() || (!o.camera_position.empty() && !o.camera_target.empty()) ||
      document.model.animations.empty() || o.animation == "none")
    return bounds;
  GltfLoadParams params{o.scene, o.variant, o.animation, 0.0f};
  const GltfLoadResult first = convert_gltf(document, params);
  if (first.playing.empty() || !first.scene.cameras.empty()) return bounds;
  float start = first.animations[first.playing[0]].start, end = first.animations[first.playing[0]].end;
  for (int a : first.playing) start = std::min(start, first.animations[a].start), end = std::max(end, first.animations[a].end);
  constexpr int kTimes = 33;
  for (int i = 0; i < kTimes; ++i) {
    params.time = start + (end - start) * static_cast<float>(i) / (kTimes - 1);
    bounds.extend(convert_gltf(document, params).scene.bounds);
  }
  return bounds;
}

}  // namespace tessera
