#include "app/cli/command_line.h"

namespace tessera {

namespace {

std::string shell_quoted(const std::string& arg) {
  static const std::string kPlain = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-+=./,:@%";
  if (!arg.empty() && arg.find_first_not_of(kPlain) == std::string::npos) return arg;
  std::string quoted = "'";
  for (char c : arg) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

void add_given(const CLI::App& app, std::vector<std::string>& names) {
  for (const CLI::Option* opt : app.get_options()) {
    if (opt->count() == 0) continue;
    names.push_back(opt->get_lnames().empty() ? opt->get_single_name() : "--" + opt->get_lnames().front());
  }
  for (const CLI::App* group : app.get_subcommands([](const CLI::App* a) { return a->get_name().empty(); }))
    add_given(*group, names);
}

}  // namespace

std::string shell_command_line(int argc, const char* const* argv) {
  std::string line;
  for (int i = 0; i < argc; ++i) line += (i ? " " : "") + shell_quoted(argv[i]);
  return line;
}

std::vector<std::string> given_options(const CLI::App& command) {
  std::vector<std::string> names;
  add_given(command, names);
  return names;
}

}  // namespace tessera
