// The input of YADE's polyhedra path (peers/yade_polyhedra.py) for a volume-linear scene: every
// body as the vertices of the mesh asperity collides with, after checking that YADE's convex
// hull of them is that body.
#pragma once

#include <nlohmann/json.hpp>

#include "solver/scene/scene.hpp"

namespace asperity::peers {

// Throws InputError (file, key, reason) for a scene the polyhedra path cannot carry: a law other
// than volume-linear, a deformable body, or a non-convex body (YADE's Polyhedra is the convex hull
// of its vertices, so a concave particle would silently become another particle).
nlohmann::ordered_json yade_polyhedra_input(const scene::SceneDef& scene, double dt, long steps);

// Largest distance of a surface vertex outside the plane of any surface face, over the body's
// size (its largest vertex distance from the centroid); 0 for a convex body up to round-off.
double convexity_defect(const Eigen::Matrix3Xd& nodes, const Eigen::Matrix3Xi& surface);

}  // namespace asperity::peers
