// Parsing tessera's command line with messages a user can act on: `tessera help [COMMAND]`
// and `tessera version`, "not a number" for a number option given text, and the nearest
// valid name for an unknown command or option ("did you mean `--width`?").
#pragma once

#include <CLI/CLI.hpp>

namespace tessera {

// Adds the help and version commands and the number checks to `app` (its commands already
// added), then parses. Returns -1 when a command is to run; else the exit code, after the
// help or version (0) or a one-line error and a pointer to --help (2).
int parse_command_line(CLI::App& app, int argc, char** argv);

}  // namespace tessera
