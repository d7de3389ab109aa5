// What the command line said: the whole command, quoted as a shell would need it (for the
// EXR header), and which options a subcommand was given (--resume fills in the others).
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace tessera {

// argv joined by spaces, each argument that a POSIX shell would split or expand in single
// quotes: pasted into a shell, it runs the same command.
std::string shell_command_line(int argc, const char* const* argv);

// The options of `command` (and of its option groups) that the parse gave at least once, by
// their first long name ("--width"), or the positional's name ("scene").
std::vector<std::string> given_options(const CLI::App& command);

}  // namespace tessera
