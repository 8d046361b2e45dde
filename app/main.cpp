// The asperity command-line program (docs/contract.md, "Commands").
#include <algorithm>
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>

#include "app/commands.hpp"
#include "cluster/world.hpp"
#include "solver/core/error.hpp"
#include "solver/core/interrupt.hpp"
#include "solver/io/printable.hpp"

namespace {

// The contract's "one line on stderr": a message quotes input (keys, file names, values), and
// input may hold newlines, control bytes or megabytes; those are escaped and cut here, once.
std::string one_line(const std::string& message) {
  return asperity::io::printable(message, 600);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace asperity;
  CLI::App cli{
      "asperity: a validation and benchmarking suite with a minimal reference FEM/DEM solver.\n"
      "Exit codes: 0 done, 1 failure (e.g. a validation case failed), 2 bad input or usage,\n"
      "3 a run went unstable (its summary.json says so)."};
  cli.require_subcommand(1);
  cli.set_version_flag("--version", "asperity 0.1.0");

  app::Action action;
  app::add_run_command(cli, action);
  app::add_validate_command(cli, action);
  app::add_crosscheck_command(cli, action);
  app::add_stability_command(cli, action);
  app::add_mesh_command(cli, action);
  app::add_particle_command(cli, action);
  app::add_study_command(cli, action);
  app::add_report_command(cli, action);
  app::add_recommend_command(cli, action);
  app::add_advise_command(cli, action);

  // CLI11 reads an unknown first word as a stray positional ("A subcommand is required").
  if (argc > 1 && argv[1][0] != '-') {
    const auto known = cli.get_subcommands([](CLI::App*) { return true; });
    if (std::none_of(known.begin(), known.end(),
                     [&](const CLI::App* c) { return c->get_name() == argv[1]; })) {
      std::string names;
      for (const CLI::App* c : known) names += (names.empty() ? "" : ", ") + c->get_name();
      std::cerr << "asperity: unknown command \"" << one_line(argv[1]) << "\" (commands: " << names
                << "; see asperity --help)\n";
      return kExitBadInput;
    }
  }
  try {
    cli.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return cli.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return cli.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return cli.exit(e);
  } catch (const CLI::ParseError& e) {
    std::string what = e.what();
    std::replace(what.begin(), what.end(), '\n', ' ');
    std::cerr << "asperity: " << one_line(what) << " (see asperity --help)\n";
    return kExitBadInput;
  }
  install_interrupt_cleanup();
  try {
    return action ? action() : kExitBadInput;
  } catch (const InputError& e) {
    // Under mpirun every rank meets the same bad input: rank 0 says it once.
    if (cluster::launched_rank() == 0) std::cerr << "asperity: " << one_line(e.what()) << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "asperity: error: " << one_line(e.what()) << "\n";
    return kExitFailure;
  }
}
