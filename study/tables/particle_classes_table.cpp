// particle_classes.csv: per particle, model and placement, the classes met at any resolution
// and the coarsest resolution's class (docs/study.md, "Classification").
#include <sstream>

#include "study/tables/tables.hpp"

namespace asperity::study::tables {

void write_particle_classes_table(const std::vector<Classification>& rows,
                                  const std::filesystem::path& dir) {
  std::vector<std::vector<OJson>> table;
  // classify_resolutions gives each (particle, model, placement) as one run of rows, coarsest
  // resolution first.
  for (std::size_t i = 0; i < rows.size();) {
    const Classification& first = rows[i];
    std::string all;
    std::size_t j = i;
    for (; j < rows.size() && rows[j].particle == first.particle && rows[j].model == first.model &&
           rows[j].placement == first.placement;
         ++j) {
      if (rows[j].cls == "overlapping") continue;
      std::istringstream parts(rows[j].cls);
      for (std::string part; std::getline(parts, part, '+');) {
        if (("+" + all + "+").find("+" + part + "+") == std::string::npos)
          all += (all.empty() ? "" : "+") + part;
      }
    }
    table.push_back({first.particle, model_name(first.model), placement_name(first.placement),
                     all.empty() ? "overlapping" : all, first.cls});
    i = j;
  }
  write_csv(dir / "particle_classes.csv",
            {"particle", "model", "placement", "classes", "coarsest_class"}, table);
}

}  // namespace asperity::study::tables
