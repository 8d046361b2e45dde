// The study's guess of each case's cost before it runs: the order the pool hands the cases out in
// (the most expensive first) and the progress line's time left (study_run.cpp), and the replay of
// that order on measured costs (schedule_estimate.hpp).
#pragma once

#include "study/study_run.hpp"

namespace asperity::study {

// Relative cost of a case for scheduling (longest first) and the time-left estimate: the FEM/DEM
// collision costs about N^1.4 (measured, docs/study.md); a rigid polyhedron has no element
// forces; the sphere is a few thousand DEM steps.
// A refined fem case's step falls with its size at the strike point: the surface triangles'
// edge over the equivalent radius is about √(29/N) (N equilateral triangles on a sphere's area
// × 1.2), so the case costs about that ratio more per step.
double case_weight(const CaseKey& c);

}  // namespace asperity::study
