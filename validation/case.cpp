// Validation cases: running and checking them.
#include "validation/case.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "solver/core/error.hpp"
#include "solver/run/stability_sweep.hpp"

namespace asperity::validation {
namespace {

std::optional<double> summary_number(const nlohmann::ordered_json& summary,
                                     const std::string& key) {
  auto it = summary.find(key);
  if (it == summary.end() || !it->is_number()) return std::nullopt;
  return it->get<double>();
}

}  // namespace

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
