// Where and how often a run writes ParaView frames (run/vtk_series.hpp), and what it wrote: plain
// data the run options and results carry.
#pragma once

#include <filesystem>

#include "solver/io/vtk_xml.hpp"

namespace asperity::run {

struct VtkOutput {
  std::filesystem::path dir;  // the series' folder (created; an earlier series in it is removed)
  int every = 0;              // steps between frames; 0 writes none
  io::vtk::Encoding encoding = io::vtk::Encoding::base64;
};

struct SeriesStats {
  long frames = 0;           // frames listed in run.pvd (the static part not counted)
  long long bytes = 0;       // bytes of every frame file written, static part included
  double write_seconds = 0;  // wall time spent on frames (copies, stresses, encoding, files), s
};

}  // namespace asperity::run
