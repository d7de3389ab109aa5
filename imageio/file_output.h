// The project's rule for every output file: write it under a temporary name beside the
// target (same directory, so the rename is atomic; same extension, so writers that choose a
// format by name still do), then rename it into place. A failed run never truncates or
// replaces an existing file.
#pragma once

#include <cstddef>
#include <functional>
#include <string>

namespace tessera {

// Throws OutputPathError (bad usage) when the directory of `path` is missing or not writable, or `path`
// exists and is not a regular file (a directory; a device such as /dev/full, a pipe or a socket, which
// renaming would replace). Call it before the work that produces the file.
void check_writable_path(const std::string& path);

// Calls write(temporary path), then renames the temporary file to `path`. Any exception
// from `write` removes the temporary file and is rethrown as OutputError naming `path`.
void write_file_atomically(const std::string& path, const std::function<void(const std::string&)>& write);

// Removes every temporary file a write_file_atomically in progress has made: for a process
// about to end at once (a second SIGINT). Async-signal-safe: it only calls unlink(2).
void remove_temporary_files();

// Writes `size` bytes to `path` (a temporary file, usually) with every write checked and an
// fsync, so a full disk or an I/O error is an OutputError, never a short file.
void write_bytes_file(const std::string& path, const void* data, std::size_t size);

// A text file (JSON, CSV, Markdown, SVG), written atomically.
void write_text_file(const std::string& path, const std::string& text);

}  // namespace tessera
