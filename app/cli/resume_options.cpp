#include "app/cli/resume_options.h"

#include <algorithm>
#include <filesystem>
#include <functional>
#include <map>
#include <sstream>
#include <type_traits>

#include <fmt/format.h>

#include "app/cli/exit_codes.h"
#include "imageio/resume_layers.h"

namespace tessera {

namespace {

// How a stored option meets the same option given again: `pixels` must be equal (they
// decide the film); a `resolved` and an `output` option given win: the resume settings
// compare what a resolved one stands for (a file's bytes, a variant's index, the camera),
// and an output's options never change the film.
enum class Role { pixels, resolved, output };

struct StoredOption {
  const char* name;  // as given_options() names it
  Role role;
  std::function<std::string(const RenderOptions&)> text;
  std::function<void(RenderOptions&, const std::string&)> set;
};

// fmt's {} writes the shortest text that reads back as the same number.
std::string to_text(const std::string& v) { return v; }
std::string to_text(bool v) { return v ? "1" : "0"; }
std::string to_text(const std::vector<std::string>& v) { return fmt::format("{}", fmt::join(v, ",")); }
template <typename T>
std::string to_text(T v) { return fmt::format("{}", v); }

void from_text(const std::string& t, std::string& v) { v = t; }
void from_text(const std::string& t, bool& v) { v = t == "1"; }
void from_text(const std::string& t, int& v) { v = std::stoi(t); }
void from_text(const std::string& t, long long& v) { v = std::stoll(t); }
void from_text(const std::string& t, float& v) { v = std::stof(t); }
void from_text(const std::string& t, double& v) { v = std::stod(t); }
void from_text(const std::string& t, std::vector<std::string>& v) {
  v.clear();
  std::istringstream in(t);
  for (std::string item; std::getline(in, item, ',');) v.push_back(item);
}

template <typename T>
StoredOption option(const char* name, Role role, T RenderOptions::*field) {
  return {name, role, [field](const RenderOptions& o) { return to_text(o.*field); },
          [field](RenderOptions& o, const std::string& t) { from_text(t, o.*field); }};
}

// A path stored absolute, so that a resume from another directory finds the same file.
std::string absolute_text(const std::string& path) {
  return path.empty() ? "" : std::filesystem::absolute(path).lexically_normal().string();
}

StoredOption path_option(const char* name, Role role, std::string RenderOptions::*field) {
  return {name, role, [field](const RenderOptions& o) { return absolute_text(o.*field); },
          [field](RenderOptions& o, const std::string& t) { o.*field = t; }};
}

// The display options (RenderOptions::display); `path`: stored absolute.
template <typename T>
StoredOption display_option(const char* name, T DisplayOptions::*field, bool path = false) {
  return {name, Role::output,
          [field, path](const RenderOptions& o) {
            if constexpr (std::is_same_v<T, std::string>) return path ? absolute_text(o.display.*field) : o.display.*field;
            else return to_text(o.display.*field);
          },
          [field](RenderOptions& o, const std::string& t) { from_text(t, o.display.*field); }};
}

const std::vector<StoredOption>& stored_options() {
  using O = RenderOptions;
  static const std::vector<StoredOption> table = {
      path_option("scene", Role::resolved, &O::scene_path),
      option("--scene", Role::pixels, &O::scene),
      option("--camera", Role::resolved, &O::camera),
      option("--look-at", Role::pixels, &O::look_at),
      option("--camera-position", Role::pixels, &O::camera_position),
      option("--camera-target", Role::pixels, &O::camera_target),
      option("--orbit", Role::pixels, &O::orbit),
      option("--variant", Role::resolved, &O::variant),
      option("--animation", Role::pixels, &O::animation),
      option("--time", Role::pixels, &O::time),
      option("--frame", Role::pixels, &O::frame),
      option("--fps", Role::pixels, &O::fps),
      option("--shutter", Role::pixels, &O::shutter),
      option("--motion-steps", Role::pixels, &O::motion_steps),
      option("--crop", Role::pixels, &O::crop),
      option("--width", Role::pixels, &O::width),
      option("--height", Role::pixels, &O::height),
      option("--resolution-scale", Role::pixels, &O::resolution_scale),
      option("--quick", Role::pixels, &O::quick),
      option("--spp", Role::pixels, &O::spp),
      option("--max-bounces", Role::pixels, &O::max_bounces),
      option("--seed", Role::pixels, &O::seed),
      option("--sampler", Role::pixels, &O::sampler),
      option("--pixel-filter", Role::pixels, &O::pixel_filter),
      option("--filter-width", Role::pixels, &O::filter_width),
      option("--aperture", Role::pixels, &O::aperture),
      option("--focus-distance", Role::pixels, &O::focus_distance),
      option("--fov", Role::pixels, &O::fov),
      option("--background", Role::pixels, &O::background),
      path_option("--envmap", Role::resolved, &O::envmap),
      option("--envmap-scale", Role::pixels, &O::envmap_scale),
      option("--envmap-rotate", Role::pixels, &O::envmap_rotate),
      option("--aov", Role::pixels, &O::aovs),
      option("--light-sampling", Role::pixels, &O::light_sampling),
      option("--light-tree", Role::pixels, &O::light_tree),
      option("--guiding", Role::pixels, &O::guiding),
      option("--clamp", Role::pixels, &O::clamp),
      option("--noise-threshold", Role::pixels, &O::noise_threshold),
      option("--min-spp", Role::pixels, &O::min_spp),
      option("--denoise", Role::pixels, &O::denoise),
      option("--film-transparent", Role::pixels, &O::film_transparent),
      path_option("--preview", Role::output, &O::preview),
      option("--half", Role::output, &O::half),
      display_option("--exposure", &DisplayOptions::exposure),
      display_option("--view-transform", &DisplayOptions::view_transform),
      display_option("--ocio-config", &DisplayOptions::ocio_config, true),
      display_option("--ocio-display", &DisplayOptions::ocio_display),
      display_option("--ocio-view", &DisplayOptions::ocio_view),
      option("--owner", Role::output, &O::owner),
      option("--comments", Role::output, &O::comments),
  };
  return table;
}

// One option a line: a newline or backslash in a value is escaped.
std::string escaped(const std::string& v) {
  std::string out;
  for (char c : v) out += c == '\n' ? std::string("\\n") : c == '\\' ? std::string("\\\\") : std::string(1, c);
  return out;
}

std::string unescaped(const std::string& v) {
  std::string out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (v[i] == '\\' && i + 1 < v.size()) out += v[++i] == 'n' ? '\n' : v[i];
    else out += v[i];
  }
  return out;
}

std::map<std::string, std::string> parse_stored(const std::string& text) {
  std::map<std::string, std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (const std::size_t eq = line.find('='); eq != std::string::npos)
      lines[line.substr(0, eq)] = unescaped(line.substr(eq + 1));
  return lines;
}

bool was_given(const RenderOptions& o, const std::string& name) {
  return std::find(o.given.begin(), o.given.end(), name) != o.given.end();
}

// "with --fov 40", or "without --fov" where the file had the option's default of none (0
// or empty); a default that means something is named ("with --background auto").
std::string rendered_with(const StoredOption& s, const std::string& value) {
  const std::string none = s.text(RenderOptions{});
  if (value == none && (none.empty() || none == "0")) return fmt::format("without {}", s.name);
  return fmt::format("with {} {}", s.name, value);
}

}  // namespace

std::string stored_options_text(const RenderOptions& o) {
  std::string text;
  for (const StoredOption& s : stored_options()) text += fmt::format("{}={}\n", s.name, escaped(s.text(o)));
  return text;
}

RenderOptions with_stored_options(const RenderOptions& given) {
  const std::string text = read_resume_options(given.resume);
  if (text.empty()) {
    if (given.scene_path.empty())
      throw UsageError(fmt::format("--resume {}: written before partial files stored their options: give the scene "
                                   "file and the options it was rendered with", given.resume));
    return given;
  }
  const std::map<std::string, std::string> stored = parse_stored(text);
  RenderOptions o = given;
  for (const StoredOption& s : stored_options()) {
    const auto it = stored.find(s.name);
    if (it == stored.end()) continue;
    const std::string& then = it->second;
    if (!was_given(given, s.name)) {
      s.set(o, then);
      continue;
    }
    const std::string now = s.text(given);
    if (s.role != Role::pixels || now == then) continue;
    if (std::string(s.name) == "--spp" && std::stoll(now) > std::stoll(then)) continue;  // a higher target
    throw UsageError(fmt::format("--resume {}: {} {} contradicts the file, rendered {}{}; leave it out to "
                                 "continue as it was started", given.resume, s.name, now, rendered_with(s, then),
                                 std::string(s.name) == "--spp" ? " (--spp may only raise the target)" : ""));
  }
  return o;
}

}  // namespace tessera
