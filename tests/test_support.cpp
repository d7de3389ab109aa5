#include "tests/test_support.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace tessera::test {

namespace fs = std::filesystem;

std::string source_dir() { return TESSERA_SOURCE_DIR; }
std::string scene_path(const std::string& relative) { return source_dir() + "/scenes/" + relative; }
std::string data_path(const std::string& relative) { return source_dir() + "/tests/data/" + relative; }
std::string tessera_exe() { return TESSERA_EXE; }

std::string make_temp_dir(const std::string& name) {
  const fs::path dir = fs::current_path() / "tmp" / (name + "-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

namespace {
std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}
}  // namespace

CommandResult run_command(const std::string& command_line) {
  static int counter = 0;
  const fs::path base = fs::current_path() / "tmp";
  fs::create_directories(base);
  const std::string stem = (base / ("cmd-" + std::to_string(::getpid()) + "-" + std::to_string(counter++))).string();
  const std::string full = "(" + command_line + ") >" + stem + ".out 2>" + stem + ".err </dev/null";
  const int status = std::system(full.c_str());
  CommandResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(stem + ".out");
  r.err = slurp(stem + ".err");
  fs::remove(stem + ".out");
  fs::remove(stem + ".err");
  return r;
}

std::string identifier(std::string text) {
  for (char& c : text)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return text;
}

std::string base64(const std::vector<std::uint8_t>& bytes) {
  static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::uint32_t n = bytes[i] << 16 | (i + 1 < bytes.size() ? bytes[i + 1] << 8 : 0) |
                            (i + 2 < bytes.size() ? bytes[i + 2] : 0);
    out += kAlphabet[n >> 18 & 63];
    out += kAlphabet[n >> 12 & 63];
    out += i + 1 < bytes.size() ? kAlphabet[n >> 6 & 63] : '=';
    out += i + 2 < bytes.size() ? kAlphabet[n & 63] : '=';
  }
  return out;
}

}  // namespace tessera::test
