// `asperity crosscheck SCENE.json --out DIR [--peer yade|lammps|liggghts|calculix ...]`: the scene
// in asperity and in each peer, side by side (peers/, docs/crosscheck.md); `asperity crosscheck
// --list --peer P`: the validation cases P's gates run or must refuse (peers/peer_policy.hpp).
#include <iostream>
#include <memory>

#include "app/cli_numbers.hpp"
#include "app/cli_options.hpp"
#include "app/commands.hpp"
#include "app/out_folder.hpp"
#include "peers/crosscheck.hpp"
#include "peers/peer.hpp"
#include "peers/peer_policy.hpp"
#include "solver/core/error.hpp"

namespace asperity::app {

namespace {

// `asperity crosscheck`: its name and its help paragraph.
constexpr CommandText kCrosscheck{
    .name = "crosscheck",
    .about =
        "Run a scene (or a validation case's scene) in asperity and in each peer at asperity's "
        "step: writes DIR/asperity/, DIR/PEER/ (summary.json, force.csv, the peer's own files), "
        "DIR/comparison.json",
};

struct CrosscheckArgs {
  peers::CrosscheckOptions o;
  std::vector<std::string> peers;
  std::string yade, lammps, liggghts, calculix;
  bool list = false;
  std::filesystem::path policy = ASPERITY_PEER_POLICY, cases = ASPERITY_CASES_DIR;
};

int crosscheck_or_list(const CrosscheckArgs& a) {
  if (a.list) {
    const std::vector<std::string> peers =
        a.peers.empty() ? std::vector<std::string>{"yade"} : a.peers;
    std::string text;
    for (const std::string& peer : peers)
      text += peers::gate_lines(peer, a.policy, peers::peer_gates(a.policy, peer, a.cases));
    std::cout << text;
    return 0;
  }
  if (a.o.scene_file.empty()) throw InputError("crosscheck: SCENE is required");
  if (a.o.out.empty()) throw InputError("crosscheck: --out is required");
  // A bad --out or --junit is exit 2 before anything runs.
  check_out_folder(a.o.out);
  if (a.o.junit) check_out_file(*a.o.junit, "--junit");
  peers::CrosscheckOptions o = a.o;
  if (!a.peers.empty()) o.peers = a.peers;
  for (const auto& [peer, exe] : {std::pair{"yade", a.yade},
                                  {"lammps", a.lammps},
                                  {"liggghts", a.liggghts},
                                  {"calculix", a.calculix}}) {
    if (!exe.empty()) o.programs[peer] = exe;
  }
  return peers::crosscheck(o);
}

}  // namespace

void add_crosscheck_command(CLI::App& app, Action& action) {
  const auto [cc, args] = add_command<CrosscheckArgs>(app, action, kCrosscheck, crosscheck_or_list);
  cc->add_option("scene", args->o.scene_file,
                 "Scene file, or a validation case file (required unless --list)");
  cc->add_option("--out", args->o.out, "Output folder (required unless --list)");
  cc->add_option("--peer", args->peers,
                 "Peer code(s): " + peers::adapter_names("|") +
                     " (default yade; repeat or comma-separate for several)")
      ->delimiter(',');
  cc->add_option("--yade", args->yade, "YADE executable (default: yade on PATH)");
  cc->add_option("--lammps", args->lammps, "LAMMPS executable (default: lmp on PATH)");
  cc->add_option("--liggghts", args->liggghts, "LIGGGHTS executable (default: liggghts on PATH)");
  cc->add_option("--calculix", args->calculix, "CalculiX executable (default: ccx on PATH)");
  cc->add_option("--max-rel-diff", args->o.max_rel_diff,
                 "Exit 1 unless peak force, impulse and contact duration agree with every peer "
                 "within this relative difference")
      ->check(real_number(0, 1e6, true));
  cc->add_option("--junit", args->o.junit,
                 "Also write JUnit XML: one testcase per peer and compared quantity");
  cc->add_flag("--only-expressible", args->o.only_expressible,
               "Run only the peers that can express the scene; list the others with their reason "
               "in comparison.json (\"not_run\") instead of exit 2");
  cc->add_flag(
      "--cost-only", args->o.cost_only,
      "Cost only: each code's plain run (no per-step recorder or dump), timed; writes "
      "DIR/cost.json (loop and whole-run CPU and wall seconds per code), compares nothing");
  add_quiet(*cc, args->o.quiet, "No summary lines on stderr");
  cc->add_flag("--list", args->list,
               "Run nothing: list on stdout the validation cases each --peer's gate runs (with its "
               "tolerance) or must refuse (with the message expected), each with its why, as "
               "--policy says (tab-separated: run|refused, case, file, ctest label, tolerance or "
               "message, why)");
  cc->add_option("--policy", args->policy,
                 "With --list: the peer policy (default validation/peer_policy.json)");
  cc->add_option("--cases", args->cases,
                 "With --list: the folder of validation cases (default validation/cases)");
}

}  // namespace asperity::app
