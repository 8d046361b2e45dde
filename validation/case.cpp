// Validation cases: loading, analytic references, running and checking.
#include "validation/case.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "solver/contact/hertz_impact.hpp"
#include "solver/core/error.hpp"
#include "solver/io/json_file.hpp"
#include "solver/run/summary_keys.hpp"
#include "solver/scene/scene_json.hpp"

namespace asperity::validation {
namespace {

using io::JsonReader;

// The analytic elastic Hertz impact of a two-body scene: a sphere against a sphere, plane or box,
// no gravity. v is the relative approach speed along the line of centres (or the wall normal).
contact::HertzImpact hertz_reference(const scene::SceneDef& s, const JsonReader& where) {
  if (s.bodies.size() != 2)
    where.fail("reference", "\"hertz\" needs a scene of exactly two bodies");
  if (s.gravity.norm() != 0) where.fail("reference", "\"hertz\" needs a scene without gravity");
  const scene::BodyDef *a = &s.bodies[0], *b = &s.bodies[1];
  if (!std::holds_alternative<scene::SphereShape>(a->shape)) std::swap(a, b);
  const auto* sa = std::get_if<scene::SphereShape>(&a->shape);
  if (!sa) where.fail("reference", "\"hertz\" needs at least one sphere");
  const Material &ma = s.materials[a->material], &mb = s.materials[b->material];
  const double mass_a = ma.density * 4.0 / 3.0 * std::numbers::pi * std::pow(sa->radius, 3);
  double r_eff = sa->radius, m_eff = mass_a, v = 0;
  if (const auto* sb = std::get_if<scene::SphereShape>(&b->shape)) {
    const double mass_b = mb.density * 4.0 / 3.0 * std::numbers::pi * std::pow(sb->radius, 3);
    r_eff = sa->radius * sb->radius / (sa->radius + sb->radius);
    if (!b->fixed) m_eff = mass_a * mass_b / (mass_a + mass_b);
    const Vec3 n = (a->position - b->position).normalized();
    v = -(a->velocity - (b->fixed ? Vec3::Zero() : b->velocity)).dot(n);
  } else if (const auto* pl = std::get_if<scene::PlaneShape>(&b->shape)) {
    v = -a->velocity.dot(pl->normal);
  } else if (const auto* bx = std::get_if<scene::BoxShape>(&b->shape)) {
    const Vec3 c = a->position.cwiseMax(bx->min).cwiseMin(bx->max);
    v = -a->velocity.dot((a->position - c).normalized());
  } else {
    where.fail("reference", "\"hertz\" needs a sphere against a sphere, plane or box");
  }
  if (!(v > 0)) where.fail("reference", "\"hertz\" needs the bodies approaching");
  return contact::hertz_impact(m_eff, r_eff, effective_young(ma, mb), v);
}

double target_restitution(const scene::SceneDef& s) {
  if (s.contact.restitution) return *s.contact.restitution;
  double e = 1;
  for (const scene::BodyDef& b : s.bodies) e = std::min(e, s.materials[b.material].restitution);
  return e;
}

std::optional<double> summary_number(const nlohmann::ordered_json& summary,
                                     const std::string& key) {
  auto it = summary.find(key);
  if (it == summary.end() || !it->is_number()) return std::nullopt;
  return it->get<double>();
}

// The summary keys a case may check (run/summary_keys.hpp, documented in docs/scenes.md): a
// misspelt quantity is bad input before anything runs, not a failed check after the run.
const std::vector<std::string_view>& checkable_keys() {
  static const std::vector<std::string_view> keys = run::summary_keys::checkable();
  return keys;
}

}  // namespace

std::string case_name_problem(const std::string& name) {
  if (name.empty()) return "must not be empty";
  if (name.size() > 200) return "longer than 200 characters";
  if (name == "." || name == "..") return "must not be \"" + name + "\" (it names a folder)";
  for (const char c : name) {
    if (c == '/' || c == '\\')
      return "must not contain a path separator (it names the case's output folder)";
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      return "must not contain control characters";
  }
  return "";
}

CaseDef load_case(const std::filesystem::path& file) {
  const io::Json json = io::read_json_file(file);
  const JsonReader r(json, file, "");
  if (!r.has("case") && r.has("bodies")) {
    r.fail("",
           "this is a scene, not a validation case (no \"case\", \"scene\" and "
           "\"expected\"); run it with asperity run");
  }
  r.only_keys({"case", "description", "tags", "source", "scene", "sweep", "expected"});
  CaseDef c;
  c.file = file;
  c.name = r.string("case");
  // The name becomes a folder under --out: a path would write outside it.
  if (const std::string problem = case_name_problem(c.name); !problem.empty())
    r.fail("case", problem);
  c.description = r.has("description") ? r.string("description") : "";
  if (r.has("tags")) {
    const JsonReader t = r.child("tags");
    for (std::size_t i = 0; i < t.require_array(); ++i) {
      if (!t.at(i).value().is_string())
        t.at(i).fail("", "must be a string (got " + io::echo(t.at(i).value()) + ")");
      c.tags.push_back(t.at(i).value().get<std::string>());
    }
  }
  r.child("scene").require_object();
  c.scene = scene::parse_scene(json.at("scene"), file, "scene");

  if (r.has("sweep")) {
    const JsonReader sw = r.child("sweep");
    sw.only_keys({"factors", "reference_factor"});
    const JsonReader f = sw.child("factors");
    std::vector<double> factors;
    for (std::size_t i = 0; i < f.require_array(); ++i) {
      const io::Json& x = f.value().at(i);
      if (!x.is_number() || !(x.get<double>() > 0)) f.fail("", "factors must be positive numbers");
      factors.push_back(x.get<double>());
    }
    if (factors.empty()) f.fail("", "empty list of factors");
    c.sweep_factors = factors;
    if (sw.has("reference_factor")) c.sweep_reference_factor = sw.positive("reference_factor");
  }
  const JsonReader ex = r.child("expected");
  ex.require_object();
  std::optional<contact::HertzImpact> hertz;
  for (const auto& [quantity, spec] : ex.value().items()) {
    const JsonReader e(spec, file, "expected." + quantity);
    const std::vector<std::string_view>& checkable = checkable_keys();
    if (std::find(checkable.begin(), checkable.end(), quantity) == checkable.end()) {
      const std::string near = io::closest_key(quantity, checkable);
      ex.fail(quantity, "not a quantity summary.json reports" +
                            (near.empty() ? std::string() : " (did you mean \"" + near + "\"?)"));
    }
    Check ch;
    ch.quantity = quantity;
    if (spec.is_string()) {  // e.g. "status": "ok"
      ch.reference = "equals";
      ch.text = spec.get<std::string>();
      c.checks.push_back(ch);
      continue;
    }
    e.only_keys({"reference", "value", "rel_tol", "abs_tol", "max", "min", "why"});
    ch.why = e.string("why");
    if (e.has("max") && e.has("min")) {
      ch.reference = "range";
      ch.expected = e.number("min");
      ch.upper = e.number("max");
    } else if (e.has("max")) {
      ch.reference = "max";
      ch.expected = e.number("max");
    } else if (e.has("min")) {
      ch.reference = "min";
      ch.expected = e.number("min");
    } else if (e.has("value")) {
      ch.reference = "value";
      ch.expected = e.number("value");
    } else {
      ch.reference = e.string("reference");
      if (ch.reference == "hertz") {
        if (!hertz) hertz = hertz_reference(c.scene, e);
        if (quantity == "peak_force")
          ch.expected = hertz->peak_force;
        else if (quantity == "max_overlap")
          ch.expected = hertz->max_overlap;
        else if (quantity == "contact_duration")
          ch.expected = hertz->contact_duration;
        else if (quantity == "impulse")
          ch.expected = hertz->impulse;
        else
          e.fail("reference",
                 "\"hertz\" gives peak_force, max_overlap, contact_duration or impulse");
      } else if (ch.reference == "target_restitution") {
        ch.expected = target_restitution(c.scene);
      } else {
        e.fail("reference", "unknown reference \"" + ch.reference +
                                "\"; expected hertz, target_restitution, or a value/max/min");
      }
    }
    if (ch.reference != "max" && ch.reference != "min" && ch.reference != "range") {
      if (!e.has("rel_tol") && !e.has("abs_tol")) e.fail("", "needs rel_tol or abs_tol");
      ch.rel_tol = e.number_or("rel_tol", 0);
      ch.abs_tol = e.number_or("abs_tol", 0);
    }
    c.checks.push_back(ch);
  }
  if (c.checks.empty()) ex.fail("", "a case must expect at least one value");
  return c;
}

std::vector<std::filesystem::path> find_cases(const std::filesystem::path& path) {
  std::vector<std::filesystem::path> out;
  if (std::filesystem::is_regular_file(path)) return {path};
  if (std::filesystem::exists(path) && !std::filesystem::is_directory(path))
    throw InputError(path.string() + ": not a regular file (a device, FIFO or socket)");
  if (!std::filesystem::is_directory(path))
    throw InputError(path.string() + ": no such case file or folder");
  for (const auto& e : std::filesystem::recursive_directory_iterator(path)) {
    if (e.is_regular_file() && e.path().extension() == ".json") out.push_back(e.path());
  }
  std::sort(out.begin(), out.end());
  if (out.empty()) throw InputError(path.string() + ": no case files (*.json) found");
  return out;
}

CaseResult run_case(const CaseDef& def) {
  if (def.sweep_factors) {
    const run::StabilityResult sweep =
        run::stability_sweep(def.scene, *def.sweep_factors, def.sweep_reference_factor);
    run::RunResult run;
    run.status = "ok";
    run.summary = sweep.summary;
    CaseResult r = check_case(def, std::move(run));
    r.sweep = sweep;
    return r;
  }
  return check_case(def, run::run_scene(def.scene));
}

CaseResult failed_case(const CaseDef& def, const std::string& error) {
  CaseResult r;
  r.def = def;
  r.run.status = "failed";
  r.error = error;
  r.passed = false;
  return r;
}

std::string check_message(const CheckResult& c) {
  std::ostringstream m;
  m.precision(8);
  m << c.check.quantity << ": got ";
  if (c.check.reference == "equals") {
    m << c.got_text << ", expected " << c.check.text;
    return m.str();
  }
  if (std::isfinite(c.got))
    m << c.got;
  else
    m << "(missing)";
  if (c.check.reference == "max") {
    m << ", expected at most " << c.check.expected;
  } else if (c.check.reference == "min") {
    m << ", expected at least " << c.check.expected;
  } else if (c.check.reference == "range") {
    m << ", expected within [" << c.check.expected << ", " << c.check.upper << "]";
  } else {
    m << ", expected " << c.check.expected << " (" << c.check.reference << ")";
    if (std::isfinite(c.got) && c.check.expected != 0)
      m << ", rel error " << (c.got - c.check.expected) / std::abs(c.check.expected);
    m << ", tolerance " << c.check.rel_tol << " rel";
    if (c.check.abs_tol != 0) m << " + " << c.check.abs_tol << " abs";
  }
  return m.str();
}

CaseResult check_case(const CaseDef& def, run::RunResult run) {
  CaseResult r;
  r.def = def;
  r.run = std::move(run);
  r.passed = true;
  for (const Check& ch : def.checks) {
    CheckResult cr;
    cr.check = ch;
    if (ch.reference == "equals") {
      auto it = r.run.summary.find(ch.quantity);
      cr.got_text = it == r.run.summary.end()
                        ? "(missing)"
                        : (it->is_string() ? it->get<std::string>() : it->dump());
      cr.passed = cr.got_text == ch.text;
    } else if (auto got = summary_number(r.run.summary, ch.quantity)) {
      cr.got = *got;
      if (ch.reference == "range")
        cr.passed = cr.got >= ch.expected && cr.got <= ch.upper;
      else if (ch.reference == "max")
        cr.passed = cr.got <= ch.expected;
      else if (ch.reference == "min")
        cr.passed = cr.got >= ch.expected;
      else
        cr.passed =
            std::abs(cr.got - ch.expected) <= ch.rel_tol * std::abs(ch.expected) + ch.abs_tol;
    } else {
      cr.got = std::nan("");
      cr.got_text = "(missing)";
      cr.passed = false;
    }
    r.passed = r.passed && cr.passed;
    r.checks.push_back(cr);
  }
  return r;
}

nlohmann::ordered_json to_json(const CaseResult& r) {
  nlohmann::ordered_json j;
  j["case"] = r.def.name;
  j["file"] = r.def.file.string();
  j["passed"] = r.passed;
  j["status"] = r.run.status;
  if (!r.error.empty()) j["error"] = r.error;
  j["checks"] = nlohmann::ordered_json::array();
  for (const CheckResult& c : r.checks) {
    nlohmann::ordered_json k;
    k["quantity"] = c.check.quantity;
    k["reference"] = c.check.reference;
    if (c.check.reference == "equals") {
      k["expected"] = c.check.text;
      k["got"] = c.got_text;
    } else {
      k["expected"] = c.check.expected;
      k["got"] = std::isfinite(c.got) ? nlohmann::ordered_json(c.got) : nlohmann::ordered_json();
      if (c.check.reference == "range") k["upper"] = c.check.upper;
      if (c.check.reference != "max" && c.check.reference != "min" &&
          c.check.reference != "range") {
        k["rel_error"] = c.check.expected != 0
                             ? (c.got - c.check.expected) / std::abs(c.check.expected)
                             : c.got - c.check.expected;
        k["rel_tol"] = c.check.rel_tol;
        k["abs_tol"] = c.check.abs_tol;
      }
    }
    k["passed"] = c.passed;
    k["why"] = c.check.why;
    j["checks"].push_back(k);
  }
  return j;
}

}  // namespace asperity::validation
