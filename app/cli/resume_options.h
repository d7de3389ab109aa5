// `--resume FILE` alone: a resumable EXR stores the options it was rendered with (the
// attribute tesseraOptions of its resume part, "--name=value" lines), and a resumed render
// takes each one the command line does not give from there. An option given that
// contradicts a stored one that decides pixels is refused, naming it; --spp may raise the
// target; paths (the scene, --envmap), --camera and --variant may be given otherwise, the
// settings then check what they stand for (app/commands/resume_settings.h: bytes, the resolved camera,
// the variant's index); outputs' options (--preview, --half, --exposure, ...) given win.
#pragma once

#include <string>

#include "app/cli/options.h"

namespace tessera {

// The stored options of `o`: the pixel-deciding ones and the outputs' (never run-only ones
// such as --threads, --time-limit or -o), paths made absolute.
std::string stored_options_text(const RenderOptions& o);

// `given` with every option it was not given taken from its --resume file. Throws
// UsageError naming an option that contradicts the file, and ResumeError for a file that
// cannot be resumed. A file from before stored options: `given` as it is (the scene file
// must then be given, as every option affecting pixels).
RenderOptions with_stored_options(const RenderOptions& given);

}  // namespace tessera
