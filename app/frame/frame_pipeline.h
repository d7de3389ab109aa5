// The pipeline every frame runs: load the glTF, plan the frame (size, camera, settings,
// environment), build the render scene, render it (resuming, checkpointing), denoise, write.
// `tessera render` runs it once; a frame sequence or an MPI rank runs the same stages, each
// as often as it needs (the scene loaded once, frames planned, built and written many times).
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "app/cli/options.h"
#include "renderer/camera/camera.h"
#include "imageio/image_output.h"
#include "renderer/render/render.h"
#include "scene_io/gltf_loader.h"

namespace tessera {

// The scene time the options ask for: --frame / --fps, else --time.
float scene_time(const RenderOptions& o);

// The syntax of the values the plan reads later (--background, --crop), checked before the
// scene is loaded so a typo costs nothing. Throws UsageError.
void check_value_syntax(const RenderOptions& o);

// Where -o goes: the option, else the resumed file (NAME.exr for NAME.partial.exr), else
// SCENE_NAME.exr in the current directory.
std::string frame_output_path(const RenderOptions& o);

// --shutter OPEN,CLOSE (frames) in seconds: {0, 0} without it. Throws UsageError.
struct Shutter {
  float open = 0.0f, close = 0.0f;
  bool on() const { return close > open; }
};
Shutter parse_shutter(const RenderOptions& o);

// Stage 1: the frame's scene from the document read once (posed at scene_time(o), with the
// shutter's motion), with the file's warnings printed when asked.
struct LoadedScene {
  GltfLoadResult gltf;
  double seconds = 0.0;
  std::uint64_t triangles = 0;  // in the file's meshes, each counted once
};
LoadedScene load_scene(const RenderOptions& o, const GltfDocument& document, bool print_warnings = true);

// Stage 2: everything decided from the options and the scene before anything is built.
// Throws UsageError for options the scene cannot satisfy.
struct FramePlan {
  RenderSettings settings;
  Camera camera;
  CameraParams camera_params;
  EnvironmentParams environment;
  std::string background;  // as the summary names it: "white (auto: no lights)", "0.5", "envmap sky.exr"
  std::string output, preview;  // checked writable
  bool cost_layer = false;  // --aov cost: CPU time per tile, from the profile
  bool denoise = false;  // --denoise: the settings carry the half buffers and features it needs
  // --variant: the KHR_materials_variants variant the loader applied (index -1, name empty: none).
  int material_variant = -1;
  std::string material_variant_name;
  bool animated = false;  // some animation posed the scene (at scene_time(o))
  DisplayParams display;  // the view of display-format outputs, checked buildable
  // What posed the scene: file scene, variant, animations, time, shutter. Two plans with the
  // same pose and environment render the same RenderScene.
  std::string pose;
};
// `framing`: the bounds the automatic camera frames instead of the scene's (null: the scene's).
FramePlan plan_frame(const RenderOptions& o, const GltfLoadResult& loaded, const Bounds3* framing = nullptr);

// The render scene of the last frame built, kept for the next frame of the same document
// (same --variant, --animation and shutter): what did not change is reused (textures, the
// environment, the BVHs of what did not move).
struct SceneCache {
  std::shared_ptr<RenderScene> scene;
  EnvironmentParams environment;
  std::string pose;  // FramePlan::pose of the scene
};

// Stage 3: the BVH, textures and lights (the description is moved in), and the camera. With
// a cache, the cached scene is used as it is when the pose and environment are the same (only
// the camera or the sampling changed), else updated to this frame where it can be, else built
// anew (and cached). Either way the image is the same, bit for bit.
struct BuiltFrame {
  std::shared_ptr<RenderScene> scene;
  RenderCamera camera;
  double seconds = 0.0;
  bool updated = false;  // the cached scene was updated, not built
};
BuiltFrame build_frame(LoadedScene loaded, const FramePlan& plan, SceneCache* cache = nullptr);

// The EXR header and write options of a frame rendered with `plan`; `partial`: some pixel is
// neither converged nor at --spp.
ImageWriteParams frame_write_params(const RenderOptions& o, const FramePlan& plan, const RenderCamera& camera,
                                    const RenderStats& stats, bool partial);

// Stage 5: denoises a frame rendered with `plan` and marks its metadata so. Returns the seconds
// it took.
double denoise_planned_frame(const FramePlan& plan, FrameImage& image, FrameMetadata& metadata);

// Stage 5 and 6: denoises a finished (not interrupted) frame when planned, then writes -o and
// --preview; a partial EXR also carries the film and settings to resume from. Returns the
// seconds spent denoising (0: not denoised).
double finish_frame(const FramePlan& plan, FrameImage& image, ImageWriteParams params, const FilmState& film,
                    const std::string& resume_text, bool denoise);

}  // namespace tessera
