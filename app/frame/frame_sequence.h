// Frame sequences: which frames --frames A:B[:STEP] asks for, where each is written
// (-o shot.####.exr, the # run becoming the zero-padded frame number, as Blender does), and
// what is already on disk (--skip-existing: finished frames are skipped, a partial one is
// continued). The frames themselves run the one frame pipeline (app/commands/render_job.h).
#pragma once

#include <string>
#include <vector>

namespace tessera {

struct FrameRange {
  int first = 0, last = 0, step = 1;
};

// "A:B" or "A:B:STEP" with 0 <= A <= B and STEP >= 1; throws UsageError otherwise.
FrameRange parse_frame_range(const std::string& text);

// The frames of the range: A, A + STEP, ... up to B.
std::vector<int> frame_numbers(const FrameRange& range);

// The output of frame `frame`: each run of '#' becomes the frame number zero-padded to the
// run's length (longer numbers are not cut); a path without '#' gets ".####" before its
// extension ("shot.exr" -> "shot.0007.exr").
std::string numbered_path(const std::string& pattern, int frame);
bool has_frame_number(const std::string& pattern);

enum class ExistingFrame { None, Finished, Partial };
// What is at `path`: nothing, a frame to keep (any file but a resumable partial EXR), or a
// partial EXR that tessera can continue with --resume.
ExistingFrame existing_frame(const std::string& path);

// Where a partial frame goes when `path` holds a finished one, which it never replaces:
// NAME.EXT -> NAME.partial.EXT beside it. finished_sibling undoes it (other paths unchanged):
// a render resumed from NAME.partial.exr writes its finished frame to NAME.exr.
std::string partial_sibling(const std::string& path);
std::string finished_sibling(const std::string& path);

}  // namespace tessera
