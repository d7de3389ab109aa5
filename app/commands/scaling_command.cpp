// tessera scaling: renders one scene with 1..N threads and each scheduler, and writes the
// speedups as a Markdown table, a CSV file and an SVG plot. With --ranks-max, also with 2..R
// MPI ranks: those runs are `tessera render` under mpirun, their figures read back from the
// render's --stats-json.
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <tuple>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "app/commands/commands.h"
#include "app/cli/exit_codes.h"
#include "app/terminal/interrupt.h"
#include "app/terminal/progress.h"
#include "app/frame/render_setup.h"
#include "app/profile/scaling_plot.h"
#include "app/profile/scaling_report.h"
#include "app/terminal/subprocess.h"
#include "app/terminal/terminal.h"
#include "imageio/file_output.h"
#include "renderer/render/render.h"

namespace tessera {

void add_scaling_command(CLI::App& app, ScalingOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "scaling", "Render a scene with 1..N threads (and 1..R MPI ranks) and each scheduler; write speedup and "
                 "efficiency as DIR/scaling.md, DIR/scaling.csv and a plot DIR/scaling.svg.");
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
  cmd->add_option("--ranks-max", o.ranks_max,
                  "Also run with 2..R MPI ranks (each with 1..--threads-max threads): `tessera render` launched "
                  "with --launcher")
      ->check(CLI::Range(1, 4096))->capture_default_str();
  cmd->add_option("--launcher", o.launcher,
                  "The command that starts a multi-rank run, {} standing for the rank count (e.g. "
                  "\"srun -n {}\" under Slurm)")
      ->capture_default_str();
  cmd->add_option("--repeat", o.repeat, "Renders of each scheduler and thread count; medians are reported")
      ->check(CLI::Range(1, 100))->capture_default_str();
  cmd->add_option("--out", o.out, "Output directory, created if missing [default: scaling-SCENE_NAME]");
  cmd->add_flag("-q,--quiet", o.quiet, "No progress and no table on standard output");
}

namespace {

struct Run {
  std::string scheduler;
  int ranks, threads;
};

// Repeats cycle through every run, so a change in the machine's load hits all runs alike.
std::vector<Run> run_order(const std::vector<std::string>& schedulers, int repeat, int ranks_max, int threads_max) {
  std::vector<Run> runs;
  for (int r = 0; r < repeat; ++r)
    for (int k = 1; k <= ranks_max; ++k)
      for (int n = 1; n <= threads_max; ++n)
        for (const std::string& s : schedulers) runs.push_back({s, k, n});
  return runs;
}

// What one render measured.
struct Measured {
  double wall = 0.0, efficiency = 1.0, imbalance = 1.0, tail = 0.0, cpu_share = 1.0;
};

Measured measured(const RenderResult& r) {
  return {r.stats.seconds, r.stats.efficiency, r.stats.imbalance, r.profile.balance.tail, r.profile.balance.cpu_share};
}

std::vector<std::string> launcher_words(const std::string& launcher, int ranks) {
  std::string line = launcher;
  for (std::size_t at = line.find("{}"); at != std::string::npos; at = line.find("{}", at))
    line.replace(at, 2, std::to_string(ranks));
  std::istringstream in(line);
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

std::string last_line(const std::string& path) {
  std::ifstream in(path);
  std::string line, last;
  while (std::getline(in, line))
    if (!line.empty()) last = line;
  return last;
}

// A run of several ranks: `tessera render` with the same settings under the launcher, its
// figures from its --stats-json (the time line and efficiency over every rank's threads).
// nullopt: interrupted.
std::optional<Measured> run_with_ranks(const ScalingOptions& o, int width, const Run& run, const std::string& dir) {
  const std::filesystem::path base = std::filesystem::path(dir) / ".run";
  const std::string json = base.string() + ".json", exr = base.string() + ".exr", log = base.string() + ".log";
  std::vector<std::string> argv = launcher_words(o.launcher, run.ranks);
  for (std::string a : {own_executable(), std::string("render"), o.scene_path, std::string("-q")}) argv.push_back(a);
  const std::vector<std::string> settings = {
      "--width", std::to_string(width), "--spp", std::to_string(o.spp), "--tile-size", std::to_string(o.tile_size),
      "--tile-order", o.tile_order, "--scheduler", run.scheduler, "--threads", std::to_string(run.threads),
      "--stats-json", json, "-o", exr};
  argv.insert(argv.end(), settings.begin(), settings.end());
  if (!o.envmap.empty()) argv.insert(argv.end(), {"--envmap", o.envmap});
  const int code = run_program(argv, log);
  if (code == kExitInterrupted) return std::nullopt;
  if (code != 0)
    throw std::runtime_error(fmt::format("{} ranks: `{}` failed with exit code {}: {}", run.ranks, argv[0], code,
                                         last_line(log)));
  std::ifstream in(json);
  const nlohmann::json stats = nlohmann::json::parse(in, nullptr, false);
  if (stats.is_discarded() || !stats.contains("frame"))
    throw std::runtime_error(fmt::format("{} ranks: the render wrote no statistics ({})", run.ranks, json));
  const nlohmann::json& f = stats["frame"];
  for (const std::string& file : {json, exr, log}) std::filesystem::remove(file);
  return Measured{f["render_seconds"], f["parallel_efficiency"], f["imbalance"], f["tail_seconds"], f["cpu_share"]};
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct Samples {
  std::vector<double> wall, efficiency, imbalance, tail, cpu_share;
};

ScalingRow summarize(const std::string& scheduler, int ranks, int threads, const Samples& s, double baseline) {
  ScalingRow row;
  row.scheduler = scheduler;
  row.ranks = ranks;
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
  report.ranks_max = o.ranks_max;
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
  if (o.ranks_max > 1) {  // Open MPI refuses root unless told (as --allow-run-as-root does)
    setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 0);
    setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 0);
  }
  std::map<std::tuple<std::string, int, int>, Samples> results;
  const std::vector<Run> runs = run_order(report.schedulers, o.repeat, o.ranks_max, report.threads_max);
  const auto start = std::chrono::steady_clock::now();
  bool interrupted = false;
  for (std::size_t i = 0; i < runs.size() && !interrupts.interrupted(); ++i) {
    const Run& run = runs[i];
    const std::string name = fmt::format("[{}/{}] {}, {}{} thread{}", i + 1, runs.size(), run.scheduler,
                                         run.ranks > 1 ? fmt::format("{} ranks x ", run.ranks) : "", run.threads,
                                         run.threads == 1 ? "" : "s");
    Measured r;
    if (run.ranks > 1) {
      if (!o.quiet) fmt::print(stderr, "{} ...\r", name);
      const std::optional<Measured> launched = run_with_ranks(o, m.width, run, dir);
      if (!launched) {
        interrupted = true;
        break;
      }
      r = *launched;
    } else {
      settings.scheduler = parse_scheduler(run.scheduler);
      settings.threads = run.threads;
      monitor.samples_done = 0;
      monitor.rays = 0;
      RenderResult result;
      {
        const std::uint64_t total = static_cast<std::uint64_t>(m.width) * m.height * o.spp;
        ProgressDisplay progress(monitor, {total, o.quiet, name + " ", true});
        result = render_frame(*m.scene, m.camera, settings, &monitor);
      }
      if (result.stats.cancelled) {
        interrupted = true;
        break;
      }
      r = measured(result);
    }
    Samples& s = results[{run.scheduler, run.ranks, run.threads}];
    s.wall.push_back(r.wall);
    s.efficiency.push_back(r.efficiency);
    s.imbalance.push_back(r.imbalance);
    s.tail.push_back(r.tail);
    s.cpu_share.push_back(r.cpu_share);
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!o.quiet)
      print_status(fmt::format("{}: {:.3f} s, efficiency {:.1f}%, imbalance {:.2f}; {} elapsed, about {} left", name,
                               r.wall, 100.0 * r.efficiency, r.imbalance, format_duration(elapsed),
                               format_duration(elapsed / (i + 1) * (runs.size() - i - 1))));
  }
  if (interrupted || interrupts.interrupted()) {
    fmt::print(stderr, "tessera: scaling interrupted; nothing written\n");
    return kExitInterrupted;
  }

  std::vector<double> one_thread;
  for (const std::string& s : report.schedulers)
    for (double w : results[{s, 1, 1}].wall) one_thread.push_back(w);
  report.baseline = median(one_thread);
  for (const std::string& s : report.schedulers)
    for (int k = 1; k <= o.ranks_max; ++k)
      for (int n = 1; n <= report.threads_max; ++n)
        report.rows.push_back(summarize(s, k, n, results[{s, k, n}], report.baseline));

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
