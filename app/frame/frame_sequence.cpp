#include "app/frame/frame_sequence.h"

#include <cstdio>
#include <filesystem>

#include <fmt/format.h>

#include "app/cli/exit_codes.h"
#include "imageio/resume_layers.h"

namespace tessera {

FrameRange parse_frame_range(const std::string& text) {
  FrameRange r;
  char tail = 0;
  const int n = std::sscanf(text.c_str(), "%d:%d%c", &r.first, &r.last, &tail);
  const bool with_step = n == 3 && tail == ':' &&
                         std::sscanf(text.c_str(), "%d:%d:%d%c", &r.first, &r.last, &r.step, &tail) == 3;
  if (!(n == 2 || with_step) || r.first < 0 || r.last < r.first || r.step < 1 || r.last > 100000000)
    throw UsageError(fmt::format("--frames {}: expected FIRST:LAST or FIRST:LAST:STEP with 0 <= FIRST <= LAST "
                                 "and STEP >= 1, e.g. 1:48 or 0:96:2",
                                 text));
  return r;
}

std::vector<int> frame_numbers(const FrameRange& range) {
  std::vector<int> frames;
  for (long long f = range.first; f <= range.last; f += range.step) frames.push_back(static_cast<int>(f));
  return frames;
}

bool has_frame_number(const std::string& pattern) {
  return std::filesystem::path(pattern).filename().string().find('#') != std::string::npos;
}

std::string numbered_path(const std::string& pattern, int frame) {
  const std::filesystem::path path(pattern);
  if (!has_frame_number(pattern)) {
    std::filesystem::path numbered = path;
    numbered.replace_filename(path.stem().string() + ".####" + path.extension().string());
    return numbered_path(numbered.string(), frame);
  }
  std::string name = path.filename().string(), out;
  for (std::size_t i = 0; i < name.size();) {
    if (name[i] != '#') {
      out += name[i++];
      continue;
    }
    std::size_t run = 0;
    while (i + run < name.size() && name[i + run] == '#') ++run;
    out += fmt::format("{:0{}d}", frame, run);
    i += run;
  }
  std::filesystem::path numbered = path;
  numbered.replace_filename(out);
  return numbered.string();
}

ExistingFrame existing_frame(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return ExistingFrame::None;
  try {
    read_resume_settings(path);  // only partial EXRs carry what resuming needs
    return ExistingFrame::Partial;
  } catch (const std::exception&) {
    return ExistingFrame::Finished;
  }
}

std::string partial_sibling(const std::string& path) {
  const std::filesystem::path p(path);
  return (p.parent_path() / (p.stem().string() + ".partial" + p.extension().string())).string();
}

std::string finished_sibling(const std::string& path) {
  const std::filesystem::path p(path);
  const std::filesystem::path stem(p.stem());
  if (stem.extension() != ".partial") return path;
  return (p.parent_path() / (stem.stem().string() + p.extension().string())).string();
}

}  // namespace tessera
