// The peers' gates from validation/peer_policy.json (peer_policy.hpp).
#include "peers/peer_policy.hpp"

#include <algorithm>
#include <charconv>
#include <optional>
#include <regex>
#include <sstream>

#include "solver/core/error.hpp"
#include "solver/io/json_file.hpp"

namespace asperity::peers {
namespace {
namespace fs = std::filesystem;

// A case name pattern: matched anywhere in the name (std::regex_search, as CMake's MATCHES).
std::regex pattern(const io::JsonReader& r, std::string_view key) {
  const std::string text = r.string(key);
  try {
    return std::regex(text, std::regex::ECMAScript);
  } catch (const std::regex_error& e) {
    r.fail(key, std::string("not a regular expression (") + e.what() + ")");
  }
}

// Every rule, tolerance and refusal says why.
std::string why_of(const io::JsonReader& r) {
  std::string why = r.string("why");
  if (why.empty()) r.fail("why", "must give the reason");
  return why;
}

std::vector<std::string> strings(const io::JsonReader& r, std::string_view key) {
  const io::JsonReader list = r.child(key);
  std::vector<std::string> out;
  const std::size_t n = list.require_array();
  for (std::size_t i = 0; i < n; ++i) {
    const io::Json& v = list.value().at(i);
    if (!v.is_string()) list.at(i).fail("", "must be a string (got " + io::echo(v) + ")");
    out.push_back(v.get<std::string>());
  }
  return out;
}

// A list of {"match": PATTERN, "why": ...}: the case names it leaves out.
std::vector<std::regex> name_exclusions(const io::JsonReader& list) {
  std::vector<std::regex> out;
  for (std::size_t i = 0, n = list.require_array(); i < n; ++i) {
    const io::JsonReader e = list.at(i);
    e.only_keys({"match", "why"});
    (void)why_of(e);
    out.push_back(pattern(e, "match"));
  }
  return out;
}

// A case left out of every sphere peer's gates: it has a top-level key, its scene has a contact
// law, or its name matches.
struct Exclusion {
  std::string key, law;
  std::optional<std::regex> match;
};

struct Rule {
  std::regex match;
  double tolerance = 0;
  std::string why;
};

struct Refusal {
  std::regex match;
  std::string expect, why;
};

// The peer's polyhedra gates (YADE's only): the cases whose name matches, but those excluded.
struct Polyhedra {
  std::regex match;
  std::vector<std::regex> exclude;
  std::vector<std::string> ci;
  double impulse = 0, peak_force = 0, contact_duration = 0;
  std::string why;  // each tolerance's, in that order
};

struct Policy {
  std::vector<std::string> shapes, models, ci;
  std::vector<Exclusion> exclude;  // every peer's
  // The peer's.
  std::string ci_label, full_label, why;
  std::vector<std::regex> peer_exclude;
  double tolerance = 0;
  std::vector<Rule> rules;
  std::vector<Refusal> refused;
  std::optional<Polyhedra> polyhedra;
};

double tolerance_of(const io::JsonReader& r) {
  return r.in_range("tolerance", 0.0, 1e6, true, false);
}

Polyhedra read_polyhedra(const io::JsonReader& r) {
  r.only_keys({"why", "cases", "exclude", "ci", "tolerances"});
  (void)why_of(r);
  Polyhedra p{.match = pattern(r, "cases"), .exclude = name_exclusions(r.child("exclude"))};
  const io::JsonReader ci = r.child("ci");
  ci.only_keys({"why", "cases"});
  (void)why_of(ci);
  p.ci = strings(ci, "cases");
  const io::JsonReader tol = r.child("tolerances");
  tol.only_keys({"impulse", "peak_force", "contact_duration"});
  for (auto [key, value] : {std::pair{"impulse", &p.impulse},
                            {"peak_force", &p.peak_force},
                            {"contact_duration", &p.contact_duration}}) {
    const io::JsonReader t = tol.child(key);
    t.only_keys({"tolerance", "why"});
    *value = tolerance_of(t);
    p.why += (p.why.empty() ? "" : "; ") + std::string(key) + ": " + why_of(t);
  }
  return p;
}

Policy read_policy(const fs::path& file, const std::string& peer) {
  const io::Json json = io::read_json_file(file);
  const io::JsonReader root(json, file, "");
  root.only_keys({"why", "sphere_cases", "ci", "peers"});
  (void)why_of(root);
  Policy p;
  const io::JsonReader sc = root.child("sphere_cases");
  sc.only_keys({"why", "shapes", "models", "exclude"});
  (void)why_of(sc);
  p.shapes = strings(sc, "shapes");
  p.models = strings(sc, "models");
  const io::JsonReader ex = sc.child("exclude");
  for (std::size_t i = 0, n = ex.require_array(); i < n; ++i) {
    const io::JsonReader e = ex.at(i);
    e.only_keys({"key", "law", "match", "why"});
    (void)why_of(e);
    Exclusion x;
    if (e.has("key")) x.key = e.string("key");
    if (e.has("law")) x.law = e.string("law");
    if (e.has("match")) x.match = pattern(e, "match");
    if ((e.has("key") ? 1 : 0) + (e.has("law") ? 1 : 0) + (e.has("match") ? 1 : 0) != 1)
      e.fail("", "give exactly one of key, law and match");
    p.exclude.push_back(std::move(x));
  }
  const io::JsonReader ci = root.child("ci");
  ci.only_keys({"why", "cases"});
  (void)why_of(ci);
  p.ci = strings(ci, "cases");
  const io::JsonReader peers = root.child("peers");
  if (!peers.has(peer)) {
    std::string known;
    for (const auto& [name, v] : peers.value().items()) known += (known.empty() ? "" : ", ") + name;
    peers.fail(peer, "no policy for peer \"" + peer + "\" (the policy has " + known + ")");
  }
  const io::JsonReader pr = peers.child(peer);
  pr.only_keys({"labels", "exclude", "tolerance", "why", "rules", "refused", "polyhedra"});
  const io::JsonReader labels = pr.child("labels");
  labels.only_keys({"ci", "full"});
  p.ci_label = labels.string("ci");
  p.full_label = labels.string("full");
  p.peer_exclude = name_exclusions(pr.child("exclude"));
  p.tolerance = tolerance_of(pr);
  p.why = why_of(pr);
  const io::JsonReader rules = pr.child("rules");
  for (std::size_t i = 0, n = rules.require_array(); i < n; ++i) {
    const io::JsonReader e = rules.at(i);
    e.only_keys({"match", "tolerance", "why"});
    p.rules.push_back(
        {.match = pattern(e, "match"), .tolerance = tolerance_of(e), .why = why_of(e)});
  }
  const io::JsonReader refused = pr.child("refused");
  for (std::size_t i = 0, n = refused.require_array(); i < n; ++i) {
    const io::JsonReader e = refused.at(i);
    e.only_keys({"match", "expect", "why"});
    (void)pattern(e, "expect");  // ctest's PASS_REGULAR_EXPRESSION: it must compile too
    p.refused.push_back(
        {.match = pattern(e, "match"), .expect = e.string("expect"), .why = why_of(e)});
  }
  if (pr.has("polyhedra")) p.polyhedra = read_polyhedra(pr.child("polyhedra"));
  return p;
}

bool found(const std::vector<std::string>& list, const std::string& s) {
  return std::find(list.begin(), list.end(), s) != list.end();
}

// Whether every body of the case's scene has one of the shapes and models (a body without a
// model is rigid); a file without a scene's bodies is no sphere case.
bool sphere_bodies(const io::Json& c, const Policy& p) {
  if (!c.is_object() || !c.contains("scene") || !c.at("scene").is_object()) return false;
  const io::Json& s = c.at("scene");
  if (!s.contains("bodies") || !s.at("bodies").is_array()) return false;
  for (const io::Json& b : s.at("bodies")) {
    if (!b.is_object() || !b.contains("shape") || !b.at("shape").is_object()) return false;
    const io::Json& shape = b.at("shape");
    if (!shape.contains("type") || !shape.at("type").is_string() ||
        !found(p.shapes, shape.at("type").get<std::string>())) {
      return false;
    }
    if (b.contains("model") &&
        !(b.at("model").is_string() && found(p.models, b.at("model").get<std::string>()))) {
      return false;
    }
  }
  return true;
}

bool excluded(const io::Json& c, const std::string& name, const Policy& p) {
  const io::Json& s = c.at("scene");
  const bool has_law = s.contains("contact") && s.at("contact").is_object() &&
                       s.at("contact").contains("law") && s.at("contact").at("law").is_string();
  for (const Exclusion& x : p.exclude) {
    if (!x.key.empty() && c.contains(x.key)) return true;
    if (!x.law.empty() && has_law && s.at("contact").at("law").get<std::string>() == x.law)
      return true;
    if (x.match && std::regex_search(name, *x.match)) return true;
  }
  for (const std::regex& re : p.peer_exclude) {
    if (std::regex_search(name, re)) return true;
  }
  return false;
}

bool polyhedra_case(const std::string& name, const Polyhedra& p) {
  if (!std::regex_search(name, p.match)) return false;
  return std::none_of(p.exclude.begin(), p.exclude.end(),
                      [&](const std::regex& re) { return std::regex_search(name, re); });
}

std::string shortest(double x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

}  // namespace

std::vector<PeerGate> peer_gates(const fs::path& policy, const std::string& peer,
                                 const fs::path& cases) {
  const Policy p = read_policy(policy, peer);
  std::vector<fs::path> files;
  for (const auto& e : fs::recursive_directory_iterator(cases)) {
    if (e.is_regular_file() && e.path().extension() == ".json") files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  std::vector<std::string> names;
  for (const fs::path& f : files) {
    std::string name = f.lexically_relative(cases).replace_extension().generic_string();
    std::replace(name.begin(), name.end(), '/', '.');
    names.push_back(std::move(name));
  }
  // A CI case that names no case file is a policy error, not a silently smaller CI subset.
  for (std::size_t i = 0; i < p.ci.size(); ++i) {
    if (!found(names, p.ci[i])) {
      throw InputError(policy.string() + ": ci.cases[" + std::to_string(i) + "]: no case \"" +
                       p.ci[i] + "\" under " + cases.string());
    }
  }
  if (p.polyhedra) {
    for (std::size_t i = 0; i < p.polyhedra->ci.size(); ++i) {
      const std::string& ci = p.polyhedra->ci[i];
      if (!found(names, ci) || !polyhedra_case(ci, *p.polyhedra)) {
        throw InputError(policy.string() + ": peers." + peer + ".polyhedra.ci.cases[" +
                         std::to_string(i) + "]: no polyhedra case \"" + ci + "\" under " +
                         cases.string());
      }
    }
  }
  std::vector<PeerGate> gates;
  for (std::size_t k = 0; k < files.size(); ++k) {
    const std::string& name = names[k];
    if (p.polyhedra && polyhedra_case(name, *p.polyhedra)) {
      const Polyhedra& ph = *p.polyhedra;
      gates.push_back({.name = name,
                       .file = files[k],
                       .label = found(ph.ci, name) ? p.ci_label : p.full_label,
                       .tolerance = std::max({ph.impulse, ph.peak_force, ph.contact_duration}),
                       .why = ph.why,
                       .polyhedra = true,
                       .impulse = ph.impulse,
                       .peak_force = ph.peak_force,
                       .contact_duration = ph.contact_duration});
      continue;
    }
    const io::Json c = io::read_json_file(files[k]);
    if (!sphere_bodies(c, p) || excluded(c, name, p)) continue;
    PeerGate g{.name = name, .file = files[k]};
    const auto refusal = std::find_if(p.refused.begin(), p.refused.end(), [&](const Refusal& r) {
      return std::regex_search(name, r.match);
    });
    if (refusal != p.refused.end()) {
      // A refusal runs nothing: its gate is in the CI label whatever the subset.
      g.label = p.ci_label;
      g.refused = true;
      g.expect = refusal->expect;
      g.why = refusal->why;
    } else {
      g.label = found(p.ci, name) ? p.ci_label : p.full_label;
      g.tolerance = p.tolerance;
      g.why = p.why;
      for (const Rule& r : p.rules) {
        if (std::regex_search(name, r.match)) {
          g.tolerance = r.tolerance;
          g.why = r.why;
          break;
        }
      }
    }
    gates.push_back(std::move(g));
  }
  return gates;
}

std::string gate_lines(const std::string& peer, const fs::path& policy,
                       const std::vector<PeerGate>& gates) {
  const auto refused =
      std::count_if(gates.begin(), gates.end(), [](const PeerGate& g) { return g.refused; });
  std::ostringstream o;
  o << "# " << peer << ": " << gates.size() - static_cast<std::size_t>(refused) << " gates run, "
    << refused << " refused (" << policy.string() << ")\n";
  for (const PeerGate& g : gates) {
    o << (g.refused     ? "refused"
          : g.polyhedra ? "polyhedra"
                        : "run")
      << '\t' << g.name << '\t' << g.file.string() << '\t' << g.label << '\t'
      << (g.refused ? g.expect : shortest(g.tolerance));
    if (g.polyhedra) {
      o << " (impulse " << shortest(g.impulse) << ", peak_force " << shortest(g.peak_force)
        << ", contact_duration " << shortest(g.contact_duration) << ")";
    }
    o << '\t' << g.why << '\n';
  }
  return o.str();
}

}  // namespace asperity::peers
