// The adapters in the table of peers.cpp, one file each (yade.cpp, lammps.cpp, liggghts.cpp).
#pragma once

#include <filesystem>

#include "peers/peer.hpp"

namespace asperity::peers {

Adapter yade_adapter();
Adapter lammps_adapter();
Adapter liggghts_adapter();

// A trace written as CSV (the YADE recorder's raw.csv): header, then per step
// t,fx,fy,fz (with `own_contact`, then s,nx,ny,nz: the peer's overlap and normal, PeerTrace)
// followed by x,y,z,vx,vy,vz of each traced body in scene order.
PeerTrace read_trace_csv(const std::filesystem::path& file, int bodies, const std::string& peer,
                         bool own_contact = false);

// The scene's free spheres, in scene order (the trace's bodies).
std::vector<int> free_spheres(const scene::SceneDef& s);

}  // namespace asperity::peers
