// A scene file read once and rendered in memory as often as asked, each render with options
// of its own (camera, size, samples, variant, time, environment, AOVs): what the Python
// module's tessera.Scene is. Each render runs the frame pipeline's stages as `tessera render`
// does (app/frame/frame_pipeline.h), on the previous render's scene updated where it can be,
// so its pixels are the command line's for the same options, bit for bit.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "app/frame/frame_pipeline.h"
#include "imageio/image_output.h"
#include "renderer/render/render.h"
#include "scene_io/gltf_loader.h"

namespace tessera {

struct SessionFrame {
  FrameImage image;
  RenderStats stats;
  ImageWriteParams write;  // what `tessera render` would write the frame with (its EXR header)
  std::vector<std::string> warnings;  // options without effect, as the command line warns
  bool cancelled = false;  // the monitor's cancel flag stopped it: the image is partial
  double load_seconds = 0.0;  // the scene posed from the document read once (stage 1)
  double build_seconds = 0.0;  // the render scene built, or the last one updated (stage 3)
  bool updated = false;  // the last render's scene was updated, not built anew
  double session_seconds = 0.0;  // the whole of FrameSession::render, as its caller timed it
};

class FrameSession {
 public:
  // Reads the file; throws SceneLoadError naming it when it cannot.
  explicit FrameSession(const std::string& path);

  // Renders with `arguments`, the render command's options as typed after the scene file
  // ("--spp", "16", "--aov", "depth"). Throws UsageError with the command line's message for
  // a bad option, and for the options that write or continue files (-o, --preview, --resume,
  // --checkpoint, --frames, profiling outputs, --pixel): a render in memory writes nothing.
  // `monitor` (optional) shows progress and stops the render early.
  SessionFrame render(const std::vector<std::string>& arguments, RenderMonitor* monitor = nullptr);

  const std::string& path() const { return path_; }
  const GltfDocument& document() const { return document_; }

 private:
  // What the automatic camera frames for the scene, variant and animations chosen: the whole
  // animation's bounds, as `tessera render` frames them (animation_bounds), found once each.
  const Bounds3& framing(const RenderOptions& o);

  std::string path_;
  GltfDocument document_;
  SceneCache cache_;  // the last render's scene, updated for the next
  std::map<std::string, Bounds3> framings_;
};

}  // namespace tessera
