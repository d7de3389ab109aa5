#include "imageio/file_output.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "imageio/image_output.h"

namespace tessera {

namespace fs = std::filesystem;

namespace {

fs::path temporary_sibling(const fs::path& target) {
  return target.parent_path() /
         (".tessera-tmp-" + std::to_string(::getpid()) + "-" + target.filename().string());
}

std::string errno_text() { return std::strerror(errno); }

// The temporary files being written, where a signal handler can read them: a slot is taken
// (used), filled, then published (ready); the handler unlinks the ready ones. A path too long
// for a slot, or a ninth write at once, goes unlisted.
struct TemporarySlot {
  std::atomic<bool> used{false}, ready{false};
  char path[4096];
};
TemporarySlot g_temporary[8];

class ListedTemporary {
 public:
  explicit ListedTemporary(const fs::path& path) {
    const std::string& text = path.native();
    if (text.size() >= sizeof(TemporarySlot::path)) return;
    for (TemporarySlot& s : g_temporary) {
      if (s.used.exchange(true)) continue;
      std::memcpy(s.path, text.c_str(), text.size() + 1);
      s.ready.store(true);
      slot_ = &s;
      return;
    }
  }
  ~ListedTemporary() {
    if (!slot_) return;
    slot_->ready.store(false);
    slot_->used.store(false);
  }
  ListedTemporary(const ListedTemporary&) = delete;
  ListedTemporary& operator=(const ListedTemporary&) = delete;

 private:
  TemporarySlot* slot_ = nullptr;
};

// Flushes the file to the disk: a delayed write error (a full disk on some file systems)
// shows here, and a crash after the rename cannot leave an empty file.
void sync_file(const fs::path& file) {
  const int fd = ::open(file.c_str(), O_RDONLY);
  if (fd < 0) throw OutputError("cannot reopen " + file.string() + ": " + errno_text());
  const int rc = ::fsync(fd);
  const std::string reason = errno_text();
  ::close(fd);
  if (rc != 0) throw OutputError("cannot be written to disk: " + reason);
}

}  // namespace

void write_bytes_file(const std::string& path, const void* data, std::size_t size) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) throw OutputError(path + ": cannot be created: " + errno_text());
  const char* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = ::write(fd, p, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const std::string reason = n < 0 ? errno_text() : "nothing written";
      ::close(fd);
      throw OutputError(path + ": " + reason);
    }
    p += n;
    size -= static_cast<std::size_t>(n);
  }
  if (::close(fd) != 0) throw OutputError(path + ": " + errno_text());
}

void check_writable_path(const std::string& path) {
  if (path.empty()) throw OutputPathError("output path is empty");
  const fs::path p(path);
  std::error_code ec;
  const fs::file_status status = fs::status(p, ec);
  if (fs::is_directory(status)) throw OutputPathError(path + ": is a directory");
  if (fs::exists(status) && !fs::is_regular_file(status))
    throw OutputPathError(path + ": is not a regular file (a device, pipe or socket): tessera writes a temporary "
                          "file beside the output and renames it into place");
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  if (!fs::is_directory(dir, ec)) throw OutputPathError(path + ": directory " + dir.string() + " does not exist");
  if (::access(dir.c_str(), W_OK) != 0) throw OutputPathError(path + ": directory " + dir.string() + " is not writable");
}

void write_file_atomically(const std::string& path, const std::function<void(const std::string&)>& write) {
  check_writable_path(path);
  const fs::path target(path);
  const fs::path tmp = temporary_sibling(target);
  const ListedTemporary listed(tmp);  // a second signal removes it
  try {
    write(tmp.string());
    sync_file(tmp);
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

void remove_temporary_files() {
  for (const TemporarySlot& s : g_temporary)
    if (s.ready.load()) ::unlink(s.path);
}

void write_text_file(const std::string& path, const std::string& text) {
  write_file_atomically(path, [&](const std::string& tmp) { write_bytes_file(tmp, text.data(), text.size()); });
}

}  // namespace tessera
