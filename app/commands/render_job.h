// One frame through the whole pipeline (app/frame/frame_pipeline.h): load it from the document
// read once, plan, build, render (resuming, checkpointing, with progress), denoise, write,
// and say what was done. `tessera render` runs it once per frame of its sequence; a rank of a
// distributed render runs it for each frame it is given.
#pragma once

#include <string>

#include "app/cli/options.h"
#include "app/frame/frame_pipeline.h"
#include "scene_io/gltf_loader.h"

namespace tessera {

struct FrameJob {
  const GltfDocument* document = nullptr;
  // The automatic camera frames these bounds (the whole animation's) instead of the frame's
  // own, so a sequence's camera stands still; null: the frame's bounds.
  const Bounds3* framing = nullptr;
  std::string label;  // starts the progress line, e.g. "frame 12 (3 of 48)"
  bool print_warnings = true;  // the file's warnings: once per sequence
  // The scene of the sequence's previous frame, updated for this one (null: built for it alone).
  SceneCache* scene_cache = nullptr;
  // The MPI ranks rendering the frame together (null: this process alone). Rank 0 shows the
  // progress, writes the outputs and checkpoints and prints the summary; the others render.
  RankGroup* ranks = nullptr;
  // The MPI ranks of a sequence whose frames they render alone (whole frames to ranks): this
  // rank tells them between waves that it is alive.
  RankGroup* alive_in = nullptr;
};

struct FrameJobResult {
  bool interrupted = false;  // a signal stopped it: the frame was written partial (or not at all)
};

// Checks -o, --preview, the profile outputs and the --resume file, which it reads: a bad one
// is refused (UsageError, ResumeError, OutputError) before anything is loaded. Returns the
// resume file's settings lines (empty without --resume).
std::string check_frame_files(const RenderOptions& options);

// Checks the frame's files (check_frame_files), then runs every stage.
FrameJobResult render_frame_job(const RenderOptions& options, const FrameJob& job);

// The bounds of everything placed, over the playing animations' time span (at up to 33
// evenly spaced times from their first key to their last): what a sequence's automatic
// camera frames. Empty bounds when no animation plays or the automatic camera is not used
// (--camera, or the file has cameras): then the 33 conversions are not made (nor, for a file
// without animations or with --animation none, even the first).
Bounds3 animation_bounds(const RenderOptions& options, const GltfDocument& document);

}  // namespace tessera
