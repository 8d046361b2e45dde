// The study key "reference" (docs/study.md, "Study file" and "The source reference"): its values
// and refusals, the source reference's cases as the planner lays them out, and the reference the
// tables take from hand-made source cases (their Richardson limit, patch check and uncertainty,
// references.csv, and every case's error measured against it).
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "solver/core/error.hpp"
#include "solver/run/impact_measures.hpp"
#include "study/study_def.hpp"
#include "study/study_run.hpp"
#include "study/tables/tables.hpp"
#include "tests/study/case_files.hpp"

namespace asperity::study::study_reference_tests {
namespace {
namespace fs = std::filesystem;
using tables::OJson;

fs::path scratch(const std::string& name) {
  return test::scratch("study_reference", name);
}

fs::path study_file(const std::string& name, const std::string& extra) {
  // A folder per file: ctest runs each test in its own process, side by side, and scratch()
  // empties its folder, so one shared folder let one test delete another's file (seen once).
  const fs::path file = scratch("def_" + name) / (name + ".json");
  std::ofstream(file) << R"({"particles": {"meshes": [{"name": "p", "file": ")"
                      << ASPERITY_SOURCE_DIR << R"(/data/meshes/particle-seed3-320.off"}]},
    "resolutions": [100], "models": ["sphere"], "placements": ["lowest"])"
                      << extra << "}";
  return file;
}

TEST(StudyReference, FinestIsTheDefaultAndSourceIsPartOfTheDefinition) {
  const StudyDef finest = load_study(study_file("finest", ""));
  EXPECT_EQ(finest.reference_kind, ReferenceKind::finest);
  // A folder written before the key keeps its study.json: "finest" adds nothing to it.
  EXPECT_FALSE(definition_json(finest).contains("reference"));
  EXPECT_TRUE(plan_source_cases(finest).empty());
  const StudyDef source =
      load_study(study_file("source", R"(, "reference": "source", "reference_patch_check": true,
                    "reference_elements_across": 2)"));
  EXPECT_EQ(source.reference_kind, ReferenceKind::source);
  EXPECT_TRUE(source.source_reference.patch_check);
  EXPECT_EQ(source.source_reference.elements_across, 2);
  const nlohmann::ordered_json j = definition_json(source);
  EXPECT_EQ(j["reference"], "source");
  EXPECT_EQ(j["reference_patch_check"], true);
  // Contact mass within a budget of 1e-4 by default, both in study.json: a folder run with
  // face-penalty, or with mass and no budget, has other levels and is refused.
  EXPECT_TRUE(source.source_reference.contact_mass);
  EXPECT_EQ(source.source_reference.added_mass, 1e-4);
  EXPECT_EQ(j["reference_contact_mass"], true);
  EXPECT_EQ(j["reference_added_mass"], 1e-4);
  const StudyDef face =
      load_study(study_file("face", R"(, "reference": "source", "reference_contact_mass": false)"));
  EXPECT_FALSE(face.source_reference.contact_mass);
  EXPECT_EQ(definition_json(face)["reference_contact_mass"], false);
  EXPECT_FALSE(definition_json(face).contains("reference_added_mass"));
  const StudyDef unbudgeted =
      load_study(study_file("unbudgeted", R"(, "reference": "source", "reference_added_mass": 0)"));
  EXPECT_EQ(definition_json(unbudgeted)["reference_added_mass"], 0);
  EXPECT_NE(first_difference(nlohmann::json::parse(definition_json(unbudgeted).dump()),
                             nlohmann::json::parse(j.dump())),
            "");
  // At most four levels by default, written only when not: a folder run before keeps its
  // study.json; 3 keeps the first round alone.
  EXPECT_EQ(source.source_reference.max_levels, 4);
  EXPECT_FALSE(j.contains("reference_max_levels"));
  const StudyDef three =
      load_study(study_file("three", R"(, "reference": "source", "reference_max_levels": 3)"));
  EXPECT_EQ(three.source_reference.max_levels, 3);
  EXPECT_EQ(definition_json(three)["reference_max_levels"], 3);
  EXPECT_EQ(load_study(study_file("four", R"(, "reference": "source", "reference_max_levels": 4)"))
                .source_reference.max_levels,
            4);
  // Another reference is another study: a folder of the one refuses the other.
  EXPECT_NE(first_difference(nlohmann::json::parse(definition_json(finest).dump()),
                             nlohmann::json::parse(j.dump())),
            "");
}

TEST(StudyReference, BadValuesAreRefusedNamingFileAndKey) {
  const std::pair<std::string, std::string> bad[] = {
      {R"(, "reference": "particle")", "reference"},
      {R"(, "reference": 1)", "reference"},
      {R"(, "reference_patch_check": true)", "reference_patch_check"},
      {R"(, "reference": "source", "reference_patch_check": "yes")", "reference_patch_check"},
      {R"(, "reference": "source", "reference_elements_across": 0.5)", "reference_elements_across"},
      {R"(, "reference": "finest", "reference_elements_across": 3)", "reference_elements_across"},
      {R"(, "reference_contact_mass": true)", "reference_contact_mass"},
      {R"(, "reference": "source", "reference_contact_mass": 1)", "reference_contact_mass"},
      {R"(, "reference_added_mass": 1e-4)", "reference_added_mass"},
      {R"(, "reference": "source", "reference_added_mass": -1e-4)", "reference_added_mass"},
      {R"(, "reference": "source", "reference_added_mass": 1)", "reference_added_mass"},
      {R"(, "reference": "source", "reference_contact_mass": false, "reference_added_mass": 1e-4)",
       "reference_added_mass"},
      {R"(, "reference": "source", "reference_max_levels": 5)", "reference_max_levels"},
      {R"(, "reference": "source", "reference_max_levels": 2)", "reference_max_levels"},
      {R"(, "reference": "source", "reference_max_levels": 3.5)", "reference_max_levels"},
      {R"(, "reference": "source", "reference_max_levels": "4")", "reference_max_levels"},
      {R"(, "reference_max_levels": 3)", "reference_max_levels"}};
  for (const auto& [extra, key] : bad) {
    try {
      load_study(study_file("bad", extra));
      ADD_FAILURE() << "accepted" << extra;
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("bad.json"), std::string::npos) << what;
      EXPECT_NE(what.find(key), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;  // one line
    }
  }
}

TEST(StudyReference, SourceCasesPerParticlePlacementPatchAndLevel) {
  StudyDef def;
  def.particles = {{.name = "a"}, {.name = "b"}};
  def.placements = {Placement::centroid, Placement::lowest};
  def.reference_kind = ReferenceKind::source;
  // 2 particles × 2 placements × 3 levels, and again on the doubled patch with the check.
  EXPECT_EQ(plan_source_cases(def).size(), 12u);
  def.source_reference.patch_check = true;
  const std::vector<CaseKey> cases = plan_source_cases(def);
  ASSERT_EQ(cases.size(), 24u);
  EXPECT_EQ(cases[0].dir_name(), "source-L1-centroid");
  EXPECT_EQ(cases[2].dir_name(), "source-L3-centroid");
  EXPECT_EQ(cases[3].dir_name(), "source-patch2-L1-centroid");
  EXPECT_EQ(cases[6].dir_name(), "source-L1-lowest");
  EXPECT_EQ(cases[12].particle, "b");
}

// The source levels at h = 0.08, 0.04, 0.02 R converging as L + c h^p per metric (p = 1.5 in
// peak force, 2 in impulse, 1 in duration), the doubled patch's levels offset by a constant.
constexpr double kPeak = 1000, kImpulse = 0.5, kDuration = 1e-4, kFirstContact = 5e-5;
constexpr double kSizes[] = {0.08, 0.04, 0.02, 0.01};  // the fourth where the first three ask
constexpr double kPatchOffset = 0.004;                 // of each limit, on the doubled patch
// The reference's peak-force term for the filter's bias on a pulse between a half-sine and Hertz's.
constexpr double kFilterTerm = run::kFilteredPeakBiasHertz - run::kFilteredPeakBiasHalfSine;

StudyDef source_def(bool patch_check) {
  StudyDef def;
  def.particles = {{.name = "p"}};
  def.resolutions = {500};
  def.reference = 500;
  def.models = {ModelKind::sphere};
  def.placements = {Placement::lowest};
  def.reference_kind = ReferenceKind::source;
  def.source_reference.patch_check = patch_check;
  return def;
}

// A source level as `asperity study` leaves it: the ringing-free peak `smooth_peak` on the patch
// (the doubled patch's scaled by 1 + kPatchOffset).
void write_source_level(const fs::path& dir, const CaseKey& k, double smooth_peak) {
  const double h = kSizes[k.level - 1], shift = k.source_patch == 2 ? 1 + kPatchOffset : 1;
  // The filtered peak is the ringing-free one less the filter's bias on Hertz's pulse
  // (source_level); the raw peak has a ringing of 3, 1, 2 and 1 % by level, no power of h,
  // which the reference must not see.
  const double smooth = smooth_peak * shift;
  const double ringing[] = {0.03, 0.01, 0.02, 0.01};
  test::write_case(dir, k,
                   {.peak = smooth * (1 + ringing[k.level - 1]),
                    .impulse = kImpulse * shift + 2 * h * h,
                    .duration = kDuration * shift + 1e-4 * h,
                    .first_contact = kFirstContact + 1e-7 * h,
                    .cpu_seconds = 10.0 * k.level,
                    .element_size_rel = h,
                    .peak_filtered = smooth * (1 - run::kFilteredPeakBiasHertz)});
}

// Every level the study asks for, the first round's and then those the folder's levels ask for
// (plan_source_cases with the folder), each at the ringing-free peak `peak(h)`.
fs::path write_source_levels(const StudyDef& def, const std::string& name,
                             const std::function<double(double)>& peak) {
  const fs::path dir = scratch(name);
  for (const CaseKey& k : plan_source_cases(def))
    write_source_level(dir, k, peak(kSizes[k.level - 1]));
  for (const CaseKey& k : plan_source_cases(def, dir)) {
    if (!fs::exists(case_dir(dir, k) / "case.json"))
      write_source_level(dir, k, peak(kSizes[k.level - 1]));
  }
  return dir;
}

fs::path write_source_study(const StudyDef& def, const std::string& name, double peak_order = 1.5) {
  const fs::path dir = write_source_levels(
      def, name, [&](double h) { return kPeak + 3000 * std::pow(h, peak_order); });
  // The sphere, 5 % above the reference in peak force, 2 % below in impulse.
  for (const CaseKey& k : plan_cases(def))
    test::write_case(dir, k,
                     {.peak = 1.05 * kPeak,
                      .impulse = 0.98 * kImpulse,
                      .duration = kDuration,
                      .first_contact = kFirstContact,
                      .cpu_seconds = 10.0 * k.level,
                      .element_size_rel = 0});
  return dir;
}

std::vector<std::vector<std::string>> read_csv(const fs::path& file) {
  std::ifstream in(file);
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> row;
    std::stringstream s(line);
    std::string cell;
    while (std::getline(s, cell, ',')) row.push_back(cell);
    if (!line.empty() && line.back() == ',') row.push_back("");
    rows.push_back(row);
  }
  return rows;
}

std::string cell(const std::vector<std::vector<std::string>>& t, std::size_t row,
                 const std::string& column) {
  for (std::size_t k = 0; k < t[0].size(); ++k) {
    if (t[0][k] == column) return k < t[row].size() ? t[row][k] : "";
  }
  ADD_FAILURE() << "no column " << column;
  return "";
}

TEST(SourceReferenceTable, LimitOrderPatchChangeAndEveryErrorAgainstTheParticle) {
  const StudyDef def = source_def(true);
  const fs::path dir = write_source_study(def, "table");
  const tables::StudyCases s = tables::load_study_cases(def, dir);
  const tables::StudyCases::Reference* r = s.reference("p", Placement::lowest);
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->kind, ReferenceKind::source);
  // A pure power law: the observed order and the limit are exact (tables::richardson's
  // bisection to 2^-100 of its bracket: 1e-9 in the order, 1e-9 relative in the limit).
  EXPECT_NEAR(r->values.peak, kPeak, 1e-9 * kPeak);
  EXPECT_NEAR(r->values.impulse, kImpulse, 1e-9 * kImpulse);
  EXPECT_NEAR(r->values.duration, kDuration, 1e-9 * kDuration);
  EXPECT_NEAR(r->source_limit[0].order, 1.5, 1e-9);
  EXPECT_NEAR(r->source_limit[1].order, 2.0, 1e-9);
  EXPECT_NEAR(r->source_limit[2].order, 1.0, 1e-9);
  // The first contact is the finest level's.
  EXPECT_DOUBLE_EQ(r->values.first_contact, kFirstContact + 1e-7 * 0.02);
  // The doubled patch's levels are the patch's scaled by 1.004 plus the same powers: at the
  // patch's weights their limit is 1.004 L exactly, a change of 0.4 % in every metric.
  ASSERT_TRUE(r->patch_checked);
  EXPECT_NEAR(r->patch.peak, kPatchOffset, 1e-9);
  EXPECT_NEAR(r->patch.impulse, kPatchOffset, 1e-9);
  EXPECT_NEAR(r->patch.duration, kPatchOffset, 1e-9);
  // The filter's shape term in peak force only (SourceMetric::filter).
  EXPECT_NEAR(r->uncertainty.peak, std::hypot(r->discretization.peak, kPatchOffset, kFilterTerm),
              1e-12);
  EXPECT_NEAR(r->uncertainty.impulse, std::hypot(r->discretization.impulse, kPatchOffset), 1e-12);
  // Roache's 1.25 times the last correction, 3000 h^1.5 at 0.02 R, over the limit.
  EXPECT_NEAR(r->discretization.peak, 1.25 * 3000 * std::pow(0.02, 1.5) / kPeak, 1e-9);
  // No geometry term: the geometry is the particle's.
  EXPECT_EQ(r->geometry_resolution, 0);
  // Every case's error is against the particle: the sphere's +5 % and −2 %.
  const tables::CaseData* sphere = s.find("p", ModelKind::sphere, 0, Placement::lowest);
  ASSERT_NE(sphere, nullptr);
  EXPECT_NEAR(s.err_fem[s.index_of(*sphere)].peak, 0.05, 1e-9);
  EXPECT_NEAR(s.err_fem[s.index_of(*sphere)].impulse, -0.02, 1e-9);
  // The classification compares with the finest level's curve.
  EXPECT_EQ(s.reference_case(*r).key.dir_name(), "source-L3-lowest");
  EXPECT_EQ(s.source_cases.size(), 6u);  // order 1.5: no fourth level

  tables::write_references_table(s, dir);
  const auto t = read_csv(dir / "references.csv");
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(cell(t, 1, "source_limit_levels"), "L1-L3");
  EXPECT_EQ(cell(t, 1, "levels"), "3");
  EXPECT_EQ(cell(t, 1, "reference"), "source");
  EXPECT_EQ(cell(t, 1, "resolution"), "");     // the source has no triangle count
  EXPECT_EQ(cell(t, 1, "geometry_from"), "");  // nor a geometry term
  EXPECT_EQ(cell(t, 1, "peak_force_geometry"), "");
  EXPECT_NEAR(std::stod(cell(t, 1, "peak_force")), kPeak, 1e-9 * kPeak);
  EXPECT_NEAR(std::stod(cell(t, 1, "impulse_source_order")), 2.0, 1e-9);
  EXPECT_EQ(cell(t, 1, "contact_duration_source_order_observed"), "true");
  EXPECT_NEAR(std::stod(cell(t, 1, "peak_force_changes_order")), 1.5, 1e-9);
  EXPECT_NEAR(std::stod(cell(t, 1, "peak_force_patch_change")), kPatchOffset, 1e-9);
  EXPECT_DOUBLE_EQ(std::stod(cell(t, 1, "peak_force_uncertainty")), r->uncertainty.peak);
}

TEST(SourceReferenceTable, SlowLevelsShowTheirOrderBesideTheAssumedOne) {
  // Peak force levels converging at order 0.24 (ballast_01's, measured): below the 0.5 the
  // extrapolation trusts, so the limit is the assumed bracket's (order 1.95, not observed), and
  // references.csv keeps the levels' own 0.24 beside it. (A fourth level ran: 0.24 is no steady
  // order; levels 2-4 show it again.)
  const StudyDef def = source_def(false);
  const fs::path dir = write_source_study(def, "slow", 0.24);
  const tables::StudyCases s = tables::load_study_cases(def, dir);
  const tables::StudyCases::Reference* r = s.reference("p", Placement::lowest);
  ASSERT_NE(r, nullptr);
  EXPECT_FALSE(r->peak.observed);
  EXPECT_DOUBLE_EQ(r->peak.order, 0.5 * (tables::kAssumedOrderLow + tables::kAssumedOrderHigh));
  EXPECT_NEAR(r->peak.changes_order, 0.24, 1e-9);
  tables::write_references_table(s, dir);
  const auto t = read_csv(dir / "references.csv");
  EXPECT_EQ(cell(t, 1, "peak_force_source_order_observed"), "false");
  EXPECT_NEAR(std::stod(cell(t, 1, "peak_force_changes_order")), 0.24, 1e-9);
  EXPECT_EQ(cell(t, 1, "source_limit_levels"), "L2-L4");
}

// The fourth level as planned from the folder (plan_source_cases with OUT): only once the first
// three on the patch finished, only where their peak force shows no steady order, on both patches,
// and never beyond "reference_max_levels".
TEST(SourceReferenceLevels, AFourthLevelIsPlannedFromTheFinishedThree) {
  StudyDef def = source_def(true);
  const auto names = [](const std::vector<CaseKey>& keys) {
    std::vector<std::string> v;
    for (const CaseKey& k : keys) v.push_back(k.dir_name());
    return v;
  };
  // rock_04-o1's levels (order 0.09).
  const double rock04[] = {99100, 100075, 100988};
  const fs::path dir = scratch("plan_l4");
  EXPECT_EQ(plan_source_cases(def, dir).size(), 6u);  // nothing ran yet: the first round
  for (const CaseKey& k : plan_source_cases(def)) write_source_level(dir, k, rock04[k.level - 1]);
  const std::vector<std::string> planned = names(plan_source_cases(def, dir));
  const std::vector<std::string> expected = {"source-L1-lowest",        "source-L2-lowest",
                                             "source-L3-lowest",        "source-L4-lowest",
                                             "source-patch2-L1-lowest", "source-patch2-L2-lowest",
                                             "source-patch2-L3-lowest", "source-patch2-L4-lowest"};
  EXPECT_EQ(planned, expected);
  // `--collect` waits for them (and for the sphere case, not written here).
  EXPECT_EQ(unfinished_cases(def, dir), 2 + 1);
  // Planned again from the same folder: the same (a rerun runs only what is missing).
  EXPECT_EQ(names(plan_source_cases(def, dir)), expected);
  // "reference_max_levels": 3, the first round alone.
  StudyDef three = def;
  three.source_reference.max_levels = 3;
  EXPECT_EQ(plan_source_cases(three, dir).size(), 6u);
  // A level of the three not finished (failed): no fourth yet.
  const CaseKey second = plan_source_cases(def)[1];
  fs::remove(case_dir(dir, second) / "case.json");
  std::ofstream(case_dir(dir, second) / "failed.json") << R"({"message": "m"})";
  EXPECT_EQ(plan_source_cases(def, dir).size(), 6u);
  // Levels at a steady order (1.5): none.
  const fs::path steady = write_source_study(def, "plan_steady");
  EXPECT_EQ(plan_source_cases(def, steady).size(), 6u);
  // Alternating levels whose last change is 0.15 % (rock_04's at the finest resolution): within
  // the 1 % (kFinerLevelAbove), none; the same shape ending in a 1.5 % change: a fourth.
  const double alternating[] = {176910, 173370, 173637};
  const fs::path alt = scratch("plan_alternating");
  for (const CaseKey& k : plan_source_cases(def))
    write_source_level(alt, k, alternating[k.level - 1]);
  EXPECT_EQ(plan_source_cases(def, alt).size(), 6u);
  const double wide[] = {176910, 170000, 172550};
  const fs::path alt_wide = scratch("plan_alternating_wide");
  for (const CaseKey& k : plan_source_cases(def))
    write_source_level(alt_wide, k, wide[k.level - 1]);
  EXPECT_EQ(plan_source_cases(def, alt_wide).size(), 8u);
}

// Four levels in the table: the limit of levels 2-4 (the hand value of
// SourceReferenceLevels.FourLevelsGiveTheLimitOfTheLastThree: L + c h² at h = 0.04, 0.02, 0.01 R,
// limit 1003 − 9/3 = 1000 N after a first level of 1060 N), which levels it is from, and the
// reference's CPU over all eight levels; a fourth level missing leaves the particle unreferenced,
// naming it.
TEST(SourceReferenceLevels, TheTableTakesTheLastThreeOfFourAndTheirCpu) {
  const StudyDef def = source_def(true);
  const fs::path dir = write_source_levels(
      def, "four", [](double h) { return h > 0.05 ? 1060 : 1000 + 30000 * h * h; });
  const tables::StudyCases s = tables::load_study_cases(def, dir);
  ASSERT_EQ(s.source_cases.size(), 8u);
  const tables::StudyCases::Reference* r = s.reference("p", Placement::lowest);
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->levels, 4);
  EXPECT_EQ(r->limit_from, 2);
  // Exact to round-off (1e-12 relative: sums of a few terms of about 1000 N, the filter's bias
  // divided out again) and the order's bisection (2^-100 of its bracket).
  EXPECT_NEAR(r->values.peak, 1000, 1e-9);
  EXPECT_NEAR(r->peak.order, 2, 1e-9);
  EXPECT_TRUE(r->peak.observed);
  EXPECT_NEAR(r->patch.peak, kPatchOffset, 1e-9);
  EXPECT_DOUBLE_EQ(r->finest_size, 0.01);
  EXPECT_EQ(s.reference_case(*r).key.dir_name(), "source-L4-lowest");
  // CPU 10 s × level on each patch: (10 + 20 + 30 + 40) × 2.
  EXPECT_DOUBLE_EQ(r->cpu, 200);
  tables::write_references_table(s, dir);
  const auto t = read_csv(dir / "references.csv");
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(cell(t, 1, "levels"), "4");
  EXPECT_EQ(cell(t, 1, "source_limit_levels"), "L2-L4");
  EXPECT_EQ(cell(t, 1, "source_finest_size_rel"), "0.01");
  EXPECT_DOUBLE_EQ(std::stod(cell(t, 1, "source_cpu_seconds")), 200);
  EXPECT_NEAR(std::stod(cell(t, 1, "peak_force")), 1000, 1e-9);

  // The fourth level on the patch missing (not run yet, or its run killed): no reference, and
  // unreferenced.csv names it.
  const CaseKey fourth{.particle = "p",
                       .model = ModelKind::fem,
                       .placement = Placement::lowest,
                       .level = 4,
                       .source_patch = 1};
  fs::remove(case_dir(dir, fourth) / "case.json");
  const tables::StudyCases u = tables::load_study_cases(def, dir);
  EXPECT_EQ(u.reference("p", Placement::lowest), nullptr);
  tables::write_unreferenced_table(u, dir);
  const auto why = read_csv(dir / "unreferenced.csv");
  ASSERT_EQ(why.size(), 2u);
  EXPECT_EQ(cell(why, 1, "why"), "source-L4-lowest missing");
}

TEST(SourceReferenceTable, PatchCheckLeftOutWhereALevelOfItFailedAndNoReferenceWithoutEveryLevel) {
  const StudyDef def = source_def(true);
  const fs::path dir = write_source_study(def, "partial");
  // A doubled-patch level failed: the reference stands, without the patch term.
  const CaseKey wide{.particle = "p",
                     .model = ModelKind::fem,
                     .placement = Placement::lowest,
                     .level = 2,
                     .source_patch = 2};
  fs::remove(case_dir(dir, wide) / "case.json");
  std::ofstream(case_dir(dir, wide) / "failed.json") << R"({"message": "m"})";
  const tables::StudyCases s = tables::load_study_cases(def, dir);
  const tables::StudyCases::Reference* r = s.reference("p", Placement::lowest);
  ASSERT_NE(r, nullptr);
  EXPECT_FALSE(r->patch_checked);
  EXPECT_DOUBLE_EQ(r->uncertainty.peak, std::hypot(r->discretization.peak, kFilterTerm));
  tables::write_references_table(s, dir);
  EXPECT_EQ(cell(read_csv(dir / "references.csv"), 1, "peak_force_patch_change"), "");
  // A level on the patch missing: no reference, so no case has an error (NaN), and no table row.
  CaseKey near = wide;
  near.source_patch = 1;
  fs::remove(case_dir(dir, near) / "case.json");
  const tables::StudyCases t = tables::load_study_cases(def, dir);
  EXPECT_EQ(t.reference("p", Placement::lowest), nullptr);
  const tables::CaseData* sphere = t.find("p", ModelKind::sphere, 0, Placement::lowest);
  ASSERT_NE(sphere, nullptr);
  EXPECT_TRUE(std::isnan(t.err_fem[t.index_of(*sphere)].peak));
  tables::write_references_table(t, dir);
  EXPECT_EQ(read_csv(dir / "references.csv").size(), 1u);  // the header alone
}

// A level of the reference that ended unstable (the run's own checks: an inverted element, energy
// growth) takes its particle out of every error; unreferenced.csv names it, the level, the status
// and the run's message, so a median "over the particles" is not silently over fewer of them.
TEST(SourceReferenceTable, AnUnstableLevelLeavesItsParticleUnreferencedAndSaysWhy) {
  const StudyDef def = source_def(false);
  const fs::path dir = write_source_study(def, "unstable");
  tables::write_unreferenced_table(tables::load_study_cases(def, dir), dir);
  EXPECT_EQ(read_csv(dir / "unreferenced.csv").size(), 1u);  // every reference made: the header
  const CaseKey finest{.particle = "p",
                       .model = ModelKind::fem,
                       .placement = Placement::lowest,
                       .level = SourceReferenceOptions{}.levels,
                       .source_patch = 1};
  std::ofstream(case_dir(dir, finest) / "summary.json")
      << R"({"status": "unstable", "message": "element 7 inverted"})";
  const tables::StudyCases s = tables::load_study_cases(def, dir);
  EXPECT_EQ(s.reference("p", Placement::lowest), nullptr);
  tables::write_unreferenced_table(s, dir);
  const auto t = read_csv(dir / "unreferenced.csv");
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(cell(t, 1, "particle"), "p");
  EXPECT_EQ(cell(t, 1, "placement"), "lowest");
  EXPECT_EQ(cell(t, 1, "why"), finest.dir_name() + " unstable: element 7 inverted");
}

}  // namespace
}  // namespace asperity::study::study_reference_tests
