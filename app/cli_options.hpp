// How a command is declared, once for every command: add_command binds its options and its action;
// and the options several commands share, each spelled, checked and bound in one place (a command
// declares `--out`, `-j`, `-q` or `--tolerance` through these, so that the same option means the
// same thing, and reads the same in --help, in every command that has it).
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "app/cli_numbers.hpp"
#include "app/commands.hpp"

namespace asperity::app {

// A command's options fill one Args, shared by the parser that fills it and the action that reads
// it. CLI11 runs the callback only once the whole command line has parsed, so the action is chosen
// there and a usage error runs nothing. (`particle` registers itself: its callback also refuses
// --seed with --set as a usage error.)
struct CommandText {
  const char* name;
  const char* about;  // the paragraph `asperity NAME --help` prints
};
template <class Args>
struct Command {
  CLI::App* cli;
  std::shared_ptr<Args> args;
};
template <class Args, class Run>
Command<Args> add_command(CLI::App& app, Action& action, const CommandText& text, Run run) {
  auto args = std::make_shared<Args>();
  CLI::App* cli = app.add_subcommand(text.name, text.about);
  cli->callback([args, run, &action] { action = [args, run] { return run(*args); }; });
  return {cli, args};
}

// `--out DIR`, required: the folder a command writes into (check_out_folder before any work).
inline CLI::Option* add_out_folder(CLI::App& cmd, std::filesystem::path& out) {
  return cmd.add_option("--out", out, "Output folder")->required();
}

// `-j,--jobs N`: worker threads, 0 (the default) for the command's own choice, which `help` names.
inline CLI::Option* add_jobs(CLI::App& cmd, int& jobs, const std::string& help) {
  return cmd.add_option("-j,--jobs", jobs, help)->check(whole_number(0, 4096));
}

// `-q,--quiet`: what it silences differs by command (`help` says which); errors are never silenced.
inline CLI::Option* add_quiet(CLI::App& cmd, bool& quiet, const std::string& help) {
  return cmd.add_flag("-q,--quiet", quiet, help);
}

// `--tolerance`: relative, "5%" or "0.05", kept as text for study::parse_tolerance to read (and
// name the option in its message) when the command runs.
inline CLI::Option* add_tolerance(CLI::App& cmd, std::string& tolerance) {
  return cmd.add_option("--tolerance", tolerance, "Relative tolerance, e.g. 5% or 0.05")
      ->capture_default_str();
}

}  // namespace asperity::app
