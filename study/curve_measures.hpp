// The study's measures of a force–time curve against its reference: shape (moments), the lag
// that aligns two curves and the class of a response (docs/study.md, "Classification"). Pure
// functions of the sampled curves; the tables (study/tables/) use them.
#pragma once

#include <string>
#include <vector>

namespace asperity::study {

// Shape measures of a force–time curve f(t) ≥ 0 and its comparison with a reference curve.
struct CurveShape {
  double mean_time = 0;  // ∫ t f dt / ∫ f dt, s
  double spread = 0;     // standard deviation of t under f, s
  double skewness = 0;   // third standardized moment of t under f (0 for a symmetric pulse)
};
CurveShape curve_shape(const std::vector<double>& t, const std::vector<double>& f);

// Time lag (s) that best aligns `f` with `ref` (maximum of their cross-correlation on a common
// uniform grid of `points` samples over [0, t_end], refined by a parabola through the peak);
// positive when `f` comes later.
double cross_correlation_lag(const std::vector<double>& t_ref, const std::vector<double>& ref,
                             const std::vector<double>& t, const std::vector<double>& f,
                             double t_end, int points = 2048);

// The classification criteria (docs/study.md, "Classification"), each tied to a tolerance of the
// guidelines: a curve classed "overlapping" is within 5 % on the first-contact shift and 10 % on
// the contact duration.
struct ClassifyCriteria {
  double shift = 0.05;      // |first-contact shift| over the reference duration above: "shifted"
  double tail = 1.10;       // contact duration over the reference's above this: "tail"
  double shortened = 0.90;  // ... below this: "short" (the stiff response)
  double asymmetry = 0.30;  // |skewness − skewness of the reference| above this: "asymmetric"
};
// "overlapping" or the criteria met, joined by '+' (e.g. "shifted+tail"). onset_shift_rel: the
// first-contact time's shift from the reference's over the reference's contact duration (not the
// cross-correlation lag, which follows the pulse width: a pulse 30 % shorter that starts at the
// same instant lags by about 15 % of the duration).
std::string classify(double onset_shift_rel, double duration_ratio, double skew_diff,
                     const ClassifyCriteria& c = {});

}  // namespace asperity::study
