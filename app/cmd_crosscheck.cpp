// `asperity crosscheck SCENE.json --out DIR [--peer yade|lammps|liggghts ...]`: the scene in
// asperity and in each peer, side by side (peers/, docs/crosscheck.md).
#include <memory>

#include "app/commands.hpp"
#include "peers/crosscheck.hpp"
#include "peers/peer.hpp"

namespace asperity::app {

void add_crosscheck_command(CLI::App& app, Action& action) {
  struct Args {
    peers::CrosscheckOptions o;
    std::vector<std::string> peers;
    std::string yade, lammps, liggghts;
  };
  auto args = std::make_shared<Args>();
  std::string names;
  for (const peers::Adapter& a : peers::adapters())
    names += std::string(names.empty() ? "" : "|") + a.name;
  auto* cc = app.add_subcommand(
      "crosscheck",
      "Run a scene (or a validation case's scene) in asperity and in each peer at asperity's "
      "step: writes DIR/asperity/, DIR/PEER/ (summary.json, force.csv, the peer's own files), "
      "DIR/comparison.json");
  cc->add_option("scene", args->o.scene_file, "Scene file, or a validation case file")->required();
  cc->add_option("--out", args->o.out, "Output folder")->required();
  cc->add_option("--peer", args->peers,
                 "Peer code(s): " + names + " (default yade; repeat or comma-separate for several)")
      ->delimiter(',');
  cc->add_option("--yade", args->yade, "YADE executable (default: yade on PATH)");
  cc->add_option("--lammps", args->lammps, "LAMMPS executable (default: lmp on PATH)");
  cc->add_option("--liggghts", args->liggghts, "LIGGGHTS executable (default: liggghts on PATH)");
  cc->add_option("--max-rel-diff", args->o.max_rel_diff,
                 "Exit 1 unless peak force, impulse and contact duration agree with every peer "
                 "within this relative difference")
      ->check(CLI::PositiveNumber);
  cc->add_option("--junit", args->o.junit,
                 "Also write JUnit XML: one testcase per peer and compared quantity");
  cc->add_flag("--only-expressible", args->o.only_expressible,
               "Run only the peers that can express the scene; list the others with their reason "
               "in comparison.json (\"not_run\") instead of exit 2");
  cc->add_flag(
      "--cost-only", args->o.cost_only,
      "Cost only: each code's plain run (no per-step recorder or dump), timed; writes "
      "DIR/cost.json (loop and whole-run CPU and wall seconds per code), compares nothing");
  cc->add_flag("-q,--quiet", args->o.quiet, "No summary lines on stderr");
  cc->callback([args, &action] {
    action = [args] {
      peers::CrosscheckOptions o = args->o;
      if (!args->peers.empty()) o.peers = args->peers;
      for (const auto& [peer, exe] : {std::pair{"yade", args->yade},
                                      {"lammps", args->lammps},
                                      {"liggghts", args->liggghts}}) {
        if (!exe.empty()) o.programs[peer] = exe;
      }
      return peers::crosscheck(o);
    };
  });
}

}  // namespace asperity::app
