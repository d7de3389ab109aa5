// Parsing tessera's command line with messages a user can act on: `tessera help [COMMAND]`
// and `tessera version`, "not a number" for a number option given text, and the nearest
// valid name for an unknown command or option ("did you mean `--width`?").
#pragma once

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace tessera {

// "tessera 0.1.0 (x86-64-v3)": the version and the instruction set this program is built for.
std::string version_line();

// Adds the help and version commands and the number checks to `app` (its commands already
// added), then parses. Returns -1 when a command is to run; else the exit code, after the
// help or version (0) or a one-line error and a pointer to --help (2).
int parse_command_line(CLI::App& app, int argc, char** argv);

// Parses `args` (a command and its arguments, as after the program's name) with the same
// checks, and throws UsageError with the message parse_command_line would print: how the
// Python module reads a render's options.
void parse_arguments(CLI::App& app, std::vector<std::string> args);

}  // namespace tessera
