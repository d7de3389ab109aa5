#include "renderer/file_output.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "renderer/image_output.h"

namespace tessera {

namespace fs = std::filesystem;

namespace {

fs::path temporary_sibling(const fs::path& target) {
  return target.parent_path() /
         (".tessera-tmp-" + std::to_string(::getpid()) + "-" + target.filename().string());
}

}  // namespace

void check_writable_path(const std::string& path) {
  if (path.empty()) throw OutputPathError("output path is empty");
  const fs::path p(path);
  std::error_code ec;
  if (fs::is_directory(p, ec)) throw OutputPathError(path + ": is a directory");
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  if (!fs::is_directory(dir, ec)) throw OutputPathError(path + ": directory " + dir.string() + " does not exist");
  if (::access(dir.c_str(), W_OK) != 0) throw OutputPathError(path + ": directory " + dir.string() + " is not writable");
}

void write_file_atomically(const std::string& path, const std::function<void(const std::string&)>& write) {
  check_writable_path(path);
  const fs::path target(path);
  const fs::path tmp = temporary_sibling(target);
  try {
    write(tmp.string());
  } catch (const std::exception& e) {
    std::error_code ec;
    fs::remove(tmp, ec);
    const std::string what = e.what();
    throw OutputError(what.rfind(path, 0) == 0 ? what : path + ": " + what);
  }
  if (std::rename(tmp.c_str(), target.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    std::error_code ec;
    fs::remove(tmp, ec);
    throw OutputError(path + ": cannot be replaced: " + reason);
  }
}

void write_text_file(const std::string& path, const std::string& text) {
  write_file_atomically(path, [&](const std::string& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    out.close();
    if (!out) throw OutputError(std::string("cannot write: ") + std::strerror(errno));
  });
}

}  // namespace tessera
