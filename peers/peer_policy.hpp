// The peers' cross-check gates as data (validation/peer_policy.json): which validation cases each
// peer's gate runs (the sphere cases; YADE's polyhedra too), at which tolerance, and which it must
// refuse, each with its why (issue 27, item 5). `asperity crosscheck --list --peer P` prints what
// peer_gates() gives, and validation/gates/peer_gates.cmake makes a test of each line.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace asperity::peers {

// One gate of a peer on one validation case.
struct PeerGate {
  std::string name;            // the case's path under the cases folder, no .json, '/' as '.'
  std::filesystem::path file;  // the case file
  std::string label;           // the policy's CI label of the peer, or its full label
  bool refused = false;        // the gate asserts that the peer refuses the case ...
  std::string expect;          // ... with a message matching this regular expression
  double tolerance = 0;        // else: the largest relative difference it accepts
  std::string why;             // the reason of the tolerance or of the refusal
  // A polyhedra gate (YADE's Polyhedra, peers.yade.polyhedra): each quantity's own tolerance,
  // `tolerance` the largest of them (crosscheck's --max-rel-diff).
  bool polyhedra = false;
  double impulse = 0, peak_force = 0, contact_duration = 0;
};

// The gates of `peer` over every case file under `cases` (sorted by path), as `policy` says.
// Throws InputError naming the policy file and key for a policy that is malformed, lacks a why,
// names an unknown peer, or holds a regular expression that does not compile.
std::vector<PeerGate> peer_gates(const std::filesystem::path& policy, const std::string& peer,
                                 const std::filesystem::path& cases);

// The gates as lines of tab-separated fields, for CMake and for reading:
//   run        NAME  FILE  LABEL  TOLERANCE  WHY
//   refused    NAME  FILE  LABEL  EXPECT     WHY
//   polyhedra  NAME  FILE  LABEL  TOLERANCE (impulse I, peak_force P, contact_duration D)  WHY
// after a first line "# ..." that names the peer, the policy and the counts.
std::string gate_lines(const std::string& peer, const std::filesystem::path& policy,
                       const std::vector<PeerGate>& gates);

}  // namespace asperity::peers
