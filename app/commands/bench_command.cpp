// tessera bench: samples/s and rays/s on fixed scenes. A measurement, not a test.
#include <algorithm>
#include <filesystem>

#include <fmt/format.h>

#include "app/cli/command_parser.h"
#include "app/commands/commands.h"
#include "app/cli/exit_codes.h"
#include "app/frame/render_setup.h"
#include "imageio/image_output.h"
#include "renderer/render/render.h"
#include "renderer/profile/traversal_ceiling.h"

#ifndef TESSERA_SCENES_DIR
#define TESSERA_SCENES_DIR "scenes"
#endif

namespace tessera {

namespace {

const std::vector<std::string>& default_bench_scenes() {
  static const std::vector<std::string> names = {
      "cornell-box/cornell-box.gltf",
      "khronos/BoxTextured/glTF-Binary/BoxTextured.glb",
      "khronos/DamagedHelmet/glTF-Binary/DamagedHelmet.glb",
      "khronos/MetalRoughSpheresNoTextures/glTF-Binary/MetalRoughSpheresNoTextures.glb",
  };
  return names;
}

struct BenchRow {
  std::string name;
  std::uint64_t triangles = 0;
  int width = 0, height = 0;
  double load_seconds = 0.0, build_seconds = 0.0;
  double median_seconds = 0.0, samples_per_second = 0.0, rays_per_second = 0.0;
  double ceiling_rays_per_second = 0.0;  // Embree alone (renderer/profile/traversal_ceiling.h), median
  double culled_share = 0.0;  // of the camera rays: not traced, their pixels' rays provably miss
};

BenchRow bench_scene(const std::string& path, const BenchOptions& o) {
  const MeasuredScene m = load_measured_scene(path, o.width);
  BenchRow row;
  row.name = std::filesystem::path(path).filename().string();
  RenderSettings settings;
  settings.width = m.width;
  settings.height = m.height;
  settings.spp = o.spp;
  settings.threads = o.threads;
  row.triangles = m.scene->geometry->instanced_triangles();
  row.width = settings.width;
  row.height = settings.height;
  row.load_seconds = m.load_seconds;
  row.build_seconds = m.build_seconds;
  // Renders and traversal-only passes alternate, so both see the same machine.
  std::vector<RenderStats> runs;
  std::vector<double> ceiling;
  TraversalCeilingParams cp{settings.width, settings.height, o.spp, settings.max_bounces, o.threads};
  cp.filter_radius = filter_reach(settings.filter);
  for (int r = 0; r < o.repeat; ++r) {
    runs.push_back(render_frame(*m.scene, m.camera, settings).stats);
    const TraversalCeilingResult c = trace_traversal_ceiling(*m.scene, m.camera, cp);
    ceiling.push_back(c.rays / c.seconds);
    row.culled_share = double(c.culled_camera_rays) / (double(settings.width) * settings.height * o.spp);
  }
  std::sort(runs.begin(), runs.end(), [](const RenderStats& a, const RenderStats& b) { return a.seconds < b.seconds; });
  std::sort(ceiling.begin(), ceiling.end());
  const RenderStats& median = runs[runs.size() / 2];
  row.median_seconds = median.seconds;
  row.samples_per_second = median.camera_samples / median.seconds;
  row.rays_per_second = median.rays / median.seconds;
  row.ceiling_rays_per_second = ceiling[ceiling.size() / 2];
  return row;
}

}  // namespace

void add_bench_command(CLI::App& app, BenchOptions& o) {
  CLI::App* cmd = app.add_subcommand("bench", "Measure samples/s and rays/s on fixed scenes (median of --repeat renders).");
  cmd->add_option("scenes", o.scenes, "glTF files [default: the benchmark scenes shipped in scenes/]");
  cmd->add_option("--spp", o.spp, "Samples per pixel")->check(CLI::Range(1, 1 << 16))->capture_default_str();
  cmd->add_option("--width", o.width, "Image width (height from the camera's aspect ratio)")
      ->check(CLI::Range(1, 8192))->capture_default_str();
  cmd->add_option("--threads", o.threads, "Render threads [default: all cores]")->check(CLI::Range(1, 1024));
  cmd->add_option("--repeat", o.repeat, "Renders per scene; the median is reported")->check(CLI::Range(1, 100))->capture_default_str();
}

int run_bench(const BenchOptions& o) {
  std::vector<std::string> scenes = o.scenes;
  if (scenes.empty())
    for (const std::string& s : default_bench_scenes()) scenes.push_back(std::string(TESSERA_SCENES_DIR) + "/" + s);
  const int threads = o.threads > 0 ? o.threads : default_thread_count();
  fmt::print("{} bench: {} spp, {} threads, median of {} renders, 8 bounces\n\n", version_line(), o.spp,
             threads, o.repeat);
  fmt::print("| scene | triangles | image | load s | build s | median s | M samples/s | M rays/s | camera rays culled "
             "| Embree alone, M rays/s | tessera / Embree alone |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const std::string& path : scenes) {
    const BenchRow r = bench_scene(path, o);
    fmt::print("| {} | {} | {}x{} | {:.3f} | {:.3f} | {:.3f} | {:.3f} | {:.3f} | {:.0f}% | {:.3f} | {:.2f} |\n", r.name,
               r.triangles, r.width, r.height, r.load_seconds, r.build_seconds, r.median_seconds,
               r.samples_per_second * 1e-6, r.rays_per_second * 1e-6, 100.0 * r.culled_share, r.ceiling_rays_per_second * 1e-6,
               r.rays_per_second / r.ceiling_rays_per_second);
    std::fflush(stdout);
  }
  fmt::print("\nEmbree alone: the same camera, image and spp traced as diffuse paths of up to {} bounces with no\n"
             "shading, lights or film (closest-hit traversal only); tessera / Embree alone is the share of a\n"
             "render's time that tracing its rays at that speed would take. Camera rays culled: those of pixels\n"
             "whose rays provably miss everything (renderer/camera/camera_coverage.h); neither traces nor counts them.\n",
             RenderSettings{}.max_bounces);
  return kExitSuccess;
}

}  // namespace tessera
