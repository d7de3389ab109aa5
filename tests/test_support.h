// Shared helpers for the tests: paths, temporary directories, running the program.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace tessera::test {

std::string source_dir();
std::string scene_path(const std::string& relative);  // under scenes/
std::string data_path(const std::string& relative);  // under tests/data/
std::string tessera_exe();

// A fresh empty directory for one test, removed by nobody (the build tree holds it).
std::string make_temp_dir(const std::string& name);

struct CommandResult {
  int exit_code = -1;
  std::string out, err;
};
// Runs a shell command line, capturing standard output and standard error.
CommandResult run_command(const std::string& command_line);

// `text` as a GoogleTest parameter name: every character but letters and digits becomes '_'.
std::string identifier(std::string text);

// Standard base64 (RFC 4648, padded): for glTF buffers built in memory as data URIs.
std::string base64(const std::vector<std::uint8_t>& bytes);

}  // namespace tessera::test
