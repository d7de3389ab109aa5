// The options of each of the tessera program's commands, one struct per command.
#pragma once

#include <string>
#include <vector>

#include "app/cli/display_options.h"

namespace tessera {

struct RenderOptions {
  std::string scene_path;
  std::string output;  // default: <scene name>.exr
  std::string preview;  // optional PNG (or any display format)
  int width = 0, height = 0;  // 0 = from the other one and the camera's aspect ratio
  int spp = 16;
  int max_bounces = 8;
  int threads = 0;
  int tile_size = 32;
  std::string scheduler = "tiles", tile_order = "scanline";
  std::string stats_json, trace, heatmap;  // load-balancing outputs, empty: none
  std::string heatmap_by = "cost";  // cost or rank
  long long seed = 0;
  std::string sampler = "sobol";
  std::string pixel_filter = "blackman-harris";
  float filter_width = 0.0f;  // 0: the filter's default
  std::string camera, scene;
  std::string variant;  // KHR_materials_variants: by name or index; empty: the default materials
  std::string animation;  // which animations play: name, index, "all" (empty: all) or "none"
  double time = 0.0;  // seconds: the scene's pose (--time)
  int frame = -1;  // --frame: time = frame / fps (-1: use --time)
  double fps = 24.0;
  std::string frames;  // --frames FIRST:LAST[:STEP]; empty: one frame
  bool skip_existing = false;
  std::string shutter;  // --shutter OPEN,CLOSE in frames; empty: no motion blur
  std::string crop;  // --crop X0,X1,Y0,Y1 (fractions of the frame); empty: the whole frame
  std::string rank_scheduler = "dynamic";  // under MPI: dynamic (a shared counter) or static
  double rank_timeout = 600.0;  // under MPI: seconds without a sign of life before a rank is given up
  DisplayOptions display;  // --exposure, --view-transform, --ocio-*
  int motion_steps = 3;
  float aperture = 0.0f, focus_distance = 0.0f, fov = 0.0f;
  std::string background = "auto";
  std::string envmap;
  float envmap_scale = 1.0f, envmap_rotate = 0.0f;
  std::vector<std::string> aovs;
  bool half = false;
  bool quiet = false;
  double time_limit = 0.0;  // seconds of sampling, 0: none
  double checkpoint = 0.0;  // seconds between checkpoints, 0: none
  std::string resume;  // a partial EXR to continue
  std::string light_sampling = "mis";
  std::string light_tree = "auto";
  std::string guiding = "auto";
  float clamp = 0.0f;
  float noise_threshold = 0.0f;  // adaptive sampling: 0 off
  int min_spp = 0;  // adaptive sampling: 0 automatic
  bool denoise = false;
  bool film_transparent = false;  // alpha = camera-ray coverage, no background in RGB
  std::string owner, comments;  // the EXR's standard owner and comments attributes
  std::string command_line;  // the whole command, for the EXR header (main sets it)
  float resolution_scale = 1.0f;  // scales the width and height (--resolution-scale)
  bool quick = false;  // --quick: a preset (app/commands/option_rules.h)
  std::string pixel;  // --pixel X,Y: trace that pixel alone and print its paths
  std::string look_at;  // --look-at EYE,TARGET,UP (nine numbers)
  std::string camera_position, camera_target;  // X,Y,Z each
  std::string orbit;  // --orbit AZIMUTH,ELEVATION[,DISTANCE]
  // The options the command line gave (long names, "--width"; "scene" for the scene file):
  // --resume takes the others from the file; the warnings about options without effect
  // name them.
  std::vector<std::string> given;
};

struct InfoOptions {
  std::string scene_path;
  std::string scene;
  double fps = 24.0;  // for the animations' frame range
  bool json = false;  // --json: the same facts as one JSON document
};

struct BenchOptions {
  std::vector<std::string> scenes;  // default: the benchmark scenes shipped in scenes/
  int spp = 16;
  int width = 640;
  int threads = 0;
  int repeat = 3;
};

struct ScalingOptions {
  std::string scene_path;
  int threads_max = 0;  // 0 = the core count
  int ranks_max = 1;  // > 1: also 2..ranks_max MPI ranks, launched with `launcher`
  std::string launcher = "mpirun --bind-to none --oversubscribe -np {}";  // {}: the rank count
  std::vector<std::string> schedulers = {"tiles", "chunks", "counter", "interleaved"};
  std::string tile_order = "scanline";
  std::string envmap;
  int spp = 16;
  int width = 480;
  int tile_size = 32;
  int repeat = 3;
  std::string out;  // default: scaling-<scene name>
  bool quiet = false;
};

struct DenoiseOptions {
  std::string input;  // an EXR with the half buffers and the albedo and normal AOVs
  std::string output;  // .exr
  std::string preview;  // optional PNG (or any display format)
  DisplayOptions display;  // the preview's look
  int threads = 0;  // 0 = all cores
  bool quiet = false;
};

}  // namespace tessera
