// tessera scaling: renders one scene with 1..N threads and each scheduler, and writes the
// speedups as a Markdown table, a CSV file and an SVG plot.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <map>

#include <fmt/format.h>

#include "app/commands.h"
#include "app/exit_codes.h"
#include "app/interrupt.h"
#include "app/progress.h"
#include "app/render_setup.h"
#include "app/scaling_plot.h"
#include "app/scaling_report.h"
#include "app/terminal.h"
#include "renderer/file_output.h"
#include "renderer/render.h"

namespace tessera {

void add_scaling_command(CLI::App& app, ScalingOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "scaling", "Render a scene with 1..N threads and each scheduler; write speedup and efficiency as "
                 "DIR/scaling.md, DIR/scaling.csv and a plot DIR/scaling.svg.");
  cmd->add_option("scene", o.scene_path, "The glTF file to render")->required();
  cmd->add_option("--threads-max", o.threads_max, "Most threads (may exceed the cores) [default: the core count]")
      ->check(CLI::Range(1, 1024));
  cmd->add_option("--schedulers", o.schedulers, "Schedulers to compare (see render --scheduler)")
      ->delimiter(',')
      ->check(CLI::IsMember(scheduler_names()))
      ->capture_default_str();
  cmd->add_option("--tile-order", o.tile_order, "Tile order for every run (see render --tile-order)")
      ->check(CLI::IsMember(tile_order_names()))->capture_default_str();
  cmd->add_option("--envmap", o.envmap, "Equirectangular environment image lighting the scene (see render --envmap)");
  cmd->add_option("--spp", o.spp, "Samples per pixel")->check(CLI::Range(1, 1 << 16))->capture_default_str();
  cmd->add_option("--width", o.width, "Image width (height from the camera's aspect ratio)")
      ->check(CLI::Range(1, 8192))->capture_default_str();
  cmd->add_option("--tile-size", o.tile_size, "Tile edge in pixels")->check(CLI::Range(1, 4096))->capture_default_str();
  cmd->add_option("--repeat", o.repeat, "Renders of each scheduler and thread count; medians are reported")
      ->check(CLI::Range(1, 100))->capture_default_str();
  cmd->add_option("--out", o.out, "Output directory, created if missing [default: scaling-SCENE_NAME]");
  cmd->add_flag("-q,--quiet", o.quiet, "No progress and no table on standard output");
}

namespace {

struct Run {
  std::string scheduler;
  int threads;
};

// Repeats cycle through every run, so a change in the machine's load hits all runs alike.
std::vector<Run> run_order(const std::vector<std::string>& schedulers, int repeat, int threads_max) {
  std::vector<Run> runs;
  for (int r = 0; r < repeat; ++r)
    for (int n = 1; n <= threads_max; ++n)
      for (const std::string& s : schedulers) runs.push_back({s, n});
  return runs;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct Samples {
  std::vector<double> wall, efficiency, imbalance, tail, cpu_share;
};

ScalingRow summarize(const std::string& scheduler, int threads, const Samples& s, double baseline) {
  ScalingRow row;
  row.scheduler = scheduler;
  row.threads = threads;
  row.wall = median(s.wall);
  row.wall_min = *std::min_element(s.wall.begin(), s.wall.end());
  row.wall_max = *std::max_element(s.wall.begin(), s.wall.end());
  row.speedup = baseline / row.wall;
  row.efficiency = median(s.efficiency);
  row.imbalance = median(s.imbalance);
  row.tail = median(s.tail);
  row.cpu_share = median(s.cpu_share);
  return row;
}

std::string output_dir(const ScalingOptions& o) {
  if (!o.out.empty()) return o.out;
  return "scaling-" + std::filesystem::path(o.scene_path).stem().string();
}

}  // namespace

int run_scaling(const ScalingOptions& o) {
  const std::string dir = output_dir(o);
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  check_writable_path((std::filesystem::path(dir) / "scaling.md").string());  // before any work

  const MeasuredScene m = load_measured_scene(o.scene_path, o.width, o.envmap);
  ScalingReport report;
  report.scene = std::filesystem::path(o.scene_path).filename().string();
  report.width = m.width;
  report.height = m.height;
  report.spp = o.spp;
  report.tile_size = o.tile_size;
  report.repeat = o.repeat;
  report.cores = default_thread_count();
  report.threads_max = o.threads_max > 0 ? o.threads_max : report.cores;
  report.tile_order = o.tile_order;
  for (const std::string& s : o.schedulers)  // each once, in the order given
    if (std::find(report.schedulers.begin(), report.schedulers.end(), s) == report.schedulers.end())
      report.schedulers.push_back(s);

  RenderSettings settings;
  settings.width = m.width;
  settings.height = m.height;
  settings.spp = o.spp;
  settings.tile_size = o.tile_size;
  settings.tile_order = parse_tile_order(o.tile_order);

  RenderMonitor monitor;
  InterruptHandler interrupts(monitor.cancel);
  std::map<std::pair<std::string, int>, Samples> results;
  const std::vector<Run> runs = run_order(report.schedulers, o.repeat, report.threads_max);
  const auto start = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < runs.size() && !interrupts.interrupted(); ++i) {
    settings.scheduler = parse_scheduler(runs[i].scheduler);
    settings.threads = runs[i].threads;
    monitor.samples_done = 0;
    monitor.rays = 0;
    const std::string name = fmt::format("[{}/{}] {}, {} thread{}", i + 1, runs.size(), runs[i].scheduler,
                                         runs[i].threads, runs[i].threads == 1 ? "" : "s");
    RenderResult r;
    {
      const std::uint64_t total = static_cast<std::uint64_t>(m.width) * m.height * o.spp;
      ProgressDisplay progress(monitor, {total, o.quiet, name + " ", true});
      r = render_frame(*m.scene, m.camera, settings, &monitor);
    }
    if (r.stats.cancelled) break;
    Samples& s = results[{runs[i].scheduler, runs[i].threads}];
    s.wall.push_back(r.stats.seconds);
    s.efficiency.push_back(r.stats.efficiency);
    s.imbalance.push_back(r.stats.imbalance);
    s.tail.push_back(r.profile.balance.tail);
    s.cpu_share.push_back(r.profile.balance.cpu_share);
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!o.quiet)
      print_status(fmt::format("{}: {:.3f} s, efficiency {:.1f}%, imbalance {:.2f}; {} elapsed, about {} left", name,
                               r.stats.seconds, 100.0 * r.stats.efficiency, r.stats.imbalance, format_duration(elapsed),
                               format_duration(elapsed / (i + 1) * (runs.size() - i - 1))));
  }
  if (interrupts.interrupted()) {
    fmt::print(stderr, "tessera: scaling interrupted; nothing written\n");
    return kExitInterrupted;
  }

  std::vector<double> one_thread;
  for (const std::string& s : report.schedulers)
    for (double w : results[{s, 1}].wall) one_thread.push_back(w);
  report.baseline = median(one_thread);
  for (const std::string& s : report.schedulers)
    for (int n = 1; n <= report.threads_max; ++n)
      report.rows.push_back(summarize(s, n, results[{s, n}], report.baseline));

  const std::filesystem::path out(dir);
  const std::string md = scaling_markdown(report);
  write_text_file((out / "scaling.md").string(), md);
  write_text_file((out / "scaling.csv").string(), scaling_csv(report));
  write_scaling_plot((out / "scaling.svg").string(), report);
  if (!o.quiet) {
    fmt::print("{}\n", md);
    print_status(fmt::format("tessera: wrote {0}/scaling.md, {0}/scaling.csv and {0}/scaling.svg", dir));
  }
  return kExitSuccess;
}

}  // namespace tessera
