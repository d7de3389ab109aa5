#include "app/cli/command_parser.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "app/cli/exit_codes.h"
#include "app/cli/nearest_name.h"
#include "imageio/image_output.h"
#include "renderer/util/isa.h"

namespace tessera {

namespace {

constexpr const char* kHelpHint = "Run 'tessera --help' or 'tessera COMMAND --help' for usage.";

int usage_error(const std::string& message) {
  fmt::print(stderr, "tessera: error: {}\n{}\n", message, kHelpHint);
  return kExitBadInput;
}

// Checked before CLI11's own conversion and range checks, which would call "abc" out of
// range: a number option's value must be a finite number, and whole for an integer.
std::string number_problem(const std::string& text, bool integer) {
  const char* begin = text.c_str();
  char* end = nullptr;
  const double value = std::strtod(begin, &end);
  if (text.empty() || end != begin + text.size()) return fmt::format("'{}' is not a number", text);
  if (!std::isfinite(value)) return fmt::format("'{}' is not a finite number", text);
  if (integer && value != std::floor(value)) return fmt::format("'{}' is not a whole number", text);
  return "";
}

void check_numbers(CLI::App& command) {
  for (CLI::Option* option : command.get_options()) {
    const std::string type = option->get_type_name();
    const bool integer = type.rfind("INT", 0) == 0 || type.rfind("UINT", 0) == 0;
    if (!integer && type.rfind("FLOAT", 0) != 0) continue;
    option->transform(CLI::Validator([integer](std::string& text) { return number_problem(text, integer); }, ""));
  }
  for (CLI::App* sub : command.get_subcommands([](CLI::App*) { return true; })) check_numbers(*sub);
}

std::vector<std::string> command_names(CLI::App& app) {
  std::vector<std::string> names;
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) names.push_back(sub->get_name());
  return names;
}

std::vector<std::string> option_names(CLI::App& command) {
  std::vector<std::string> names;
  for (CLI::Option* option : command.get_options()) {
    for (const std::string& l : option->get_lnames()) names.push_back("--" + l);
    for (const std::string& s : option->get_snames()) names.push_back("-" + s);
  }
  return names;
}

std::string did_you_mean(const std::string& typed, const std::vector<std::string>& names) {
  const std::string near = nearest_name(typed, names);
  return near.empty() ? "" : fmt::format(" (did you mean `{}`?)", near);
}

// A first argument that is no command (and no option of tessera's own): the nearest command.
// Empty when it is one.
std::string command_name_problem(CLI::App& app, const std::string& first) {
  if (first.empty()) return "";
  if (first[0] == '-') {
    const std::string name = first.substr(0, first.find('='));
    const std::vector<std::string> names = option_names(app);
    if (std::find(names.begin(), names.end(), name) != names.end()) return "";
    return fmt::format("unknown option {}{}", name, did_you_mean(name, names));
  }
  const std::vector<std::string> names = command_names(app);
  if (std::find(names.begin(), names.end(), first) != names.end()) return "";
  return fmt::format("unknown command '{}'{}", first, did_you_mean(first, names));
}

int check_command_name(CLI::App& app, const std::string& first) {
  const std::string problem = command_name_problem(app, first);
  return problem.empty() ? -1 : usage_error(problem);
}

// An argument the command did not expect: the nearest option when it looks like one.
std::string explain_extras(CLI::App& app, const CLI::ExtrasError& e) {
  const std::vector<CLI::App*> chosen = app.get_subcommands();
  CLI::App& command = chosen.empty() ? app : *chosen.back();
  for (const std::string& arg : command.remaining()) {
    if (arg.size() < 2 || arg[0] != '-' || std::isdigit(static_cast<unsigned char>(arg[1]))) continue;
    const std::string name = arg.substr(0, arg.find('='));
    return fmt::format("{}: unknown option {}{}", command.get_name(), name, did_you_mean(name, option_names(command)));
  }
  return e.what();
}

// The message for a parse error other than a call for help or the version.
std::string parse_problem(CLI::App& app, const CLI::ParseError& e) {
  if (const auto* extras = dynamic_cast<const CLI::ExtrasError*>(&e)) return explain_extras(app, *extras);
  const std::string text = e.what();
  // CLI11: "--spp: At Most 1 required but received 2"
  const std::size_t colon = dynamic_cast<const CLI::ArgumentMismatch*>(&e) ? text.find(": At Most 1 required")
                                                                            : std::string::npos;
  return colon == std::string::npos ? text : text.substr(0, colon) + ": given more than once";
}

}  // namespace

std::string version_line() { return fmt::format("tessera {} ({})", tessera_version(), compiled_isa()); }

int parse_command_line(CLI::App& app, int argc, char** argv) {
  std::string topic;
  app.add_subcommand("help", "Print this help, or a command's: tessera help render")
      ->add_option("command", topic, "The command to explain");
  app.add_subcommand("version", "Print the version");
  check_numbers(app);
  if (argc < 2) {
    std::string names;
    for (const std::string& n : command_names(app)) names += (names.empty() ? "" : ", ") + n;
    return usage_error("no command given; the commands are " + names);
  }
  if (const int code = check_command_name(app, argv[1]); code >= 0) return code;
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    return usage_error(parse_problem(app, e));
  }
  if (app.got_subcommand("version")) {
    fmt::print("{}\n", version_line());
    return kExitSuccess;
  }
  if (!app.got_subcommand("help")) return -1;
  if (topic.empty()) {
    fmt::print("{}", app.get_formatter()->make_help(&app, app.get_name(), CLI::AppFormatMode::Normal));
    return kExitSuccess;
  }
  const int code = check_command_name(app, topic);
  if (code >= 0) return code;
  fmt::print("{}", app.get_subcommand(topic)->help(app.get_name()));
  return kExitSuccess;
}

void parse_arguments(CLI::App& app, std::vector<std::string> args) {
  check_numbers(app);
  if (const std::string problem = command_name_problem(app, args.empty() ? "" : args[0]); !problem.empty())
    throw UsageError(problem);
  std::reverse(args.begin(), args.end());  // CLI11 takes them last first
  try {
    app.parse(args);
  } catch (const CLI::ParseError& e) {
    throw UsageError(parse_problem(app, e));
  }
}

}  // namespace tessera
