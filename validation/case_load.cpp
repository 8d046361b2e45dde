// Validation cases: loading them and their analytic references (a file of its own, so that the
// case fuzzer, tests/fuzz/fuzz_case.cpp, builds without the runners).
#include "validation/case.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "solver/contact/hertz_impact.hpp"
#include "solver/core/error.hpp"
#include "solver/io/json_file.hpp"
#include "solver/io/plain_name.hpp"
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

// The summary keys a case may check (run/summary_keys.hpp, documented in docs/scenes.md): a
// misspelt quantity is bad input before anything runs, not a failed check after the run.
const std::vector<std::string_view>& checkable_keys() {
  static const std::vector<std::string_view> keys = run::summary_keys::checkable();
  return keys;
}

}  // namespace

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
  if (const std::string problem = io::plain_name_problem(c.name); !problem.empty())
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
    // At most the predicted critical step: a reference beyond it may be unstable.
    if (sw.has("reference_factor"))
      c.sweep_reference_factor = sw.in_range("reference_factor", 0, 1, true, false);
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
      // A negative tolerance fails every value: bad input, not a failed check after the run.
      if (e.has("rel_tol")) ch.rel_tol = e.in_range("rel_tol", 0, 1e6, false, false);
      if (e.has("abs_tol")) ch.abs_tol = e.in_range("abs_tol", 0, 1e300, false, false);
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

}  // namespace asperity::validation
