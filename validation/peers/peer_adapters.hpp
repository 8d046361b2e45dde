// The adapters in the table of peers.cpp, one file each (yade.cpp, lammps.cpp, liggghts.cpp).
#pragma once

#include <filesystem>

#include "peer.hpp"

namespace asperity::peers {

Adapter yade_adapter();
Adapter lammps_adapter();
Adapter liggghts_adapter();

// A trace written as CSV (the YADE recorder's raw.csv): header, then per step
// t,fx,fy,fz followed by x,y,z,vx,vy,vz of each free sphere in scene order.
PeerTrace read_trace_csv(const std::filesystem::path& file, int free_spheres,
                         const std::string& peer);

// The scene's free spheres, in scene order (the trace's bodies).
std::vector<int> free_spheres(const scene::SceneDef& s);

}  // namespace asperity::peers
