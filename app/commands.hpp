// One file per command: each registers its CLI11 subcommand and the action that runs it (through
// add_command, app/cli_options.hpp).
#pragma once

#include <functional>

#include <CLI/CLI.hpp>

namespace asperity::app {

// The action returns the process exit code (core/error.hpp); it may throw InputError (exit 2).
using Action = std::function<int()>;

void add_run_command(CLI::App& app, Action& action);
void add_validate_command(CLI::App& app, Action& action);
void add_crosscheck_command(CLI::App& app, Action& action);
void add_stability_command(CLI::App& app, Action& action);
void add_mesh_command(CLI::App& app, Action& action);
void add_particle_command(CLI::App& app, Action& action);
void add_study_command(CLI::App& app, Action& action);
void add_report_command(CLI::App& app, Action& action);
void add_recommend_command(CLI::App& app, Action& action);
void add_advise_command(CLI::App& app, Action& action);

}  // namespace asperity::app
