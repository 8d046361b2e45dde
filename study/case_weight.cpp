// The study's cost guess per case (case_weight.hpp).
#include "study/case_weight.hpp"

#include <algorithm>
#include <cmath>

#include "study/source_reference.hpp"

namespace asperity::study {

double case_weight(const CaseKey& c) {
  if (c.source_patch > 0) {
    // As a refined case at 2000 triangles whose size halves per level from the median finest
    // a/3 (a/R 0.065, docs/study.md "The source reference"): they run first.
    const double size = 0.065 / 3 * std::pow(2.0, SourceReferenceOptions{}.levels - c.level);
    return std::pow(20.0, 1.4) * std::sqrt(29.0 / 2000.0) / size;
  }
  const double n = std::pow(static_cast<double>(c.resolution) / 100.0, 1.4);
  switch (c.model) {
    case ModelKind::fem:
      if (c.level > 0) {
        const double edge = std::sqrt(29.0 / static_cast<double>(c.resolution));
        return n * std::max(1.0, edge / c.relative_size);
      }
      return n;
    case ModelKind::rigid:
    case ModelKind::rigid_penalty:
      return 0.5 * n;
    case ModelKind::sphere:
    case ModelKind::sphere_local:
      return 0.01;
  }
  return 1;
}

}  // namespace asperity::study
