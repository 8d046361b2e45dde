// Reading surface meshes from STL (ASCII and binary), OBJ, PLY (ASCII and binary) and OFF into a
// polygon soup, with one-line errors that name the file and the defect.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include <Eigen/Core>

namespace asperity::geometry {

// What a file holds before any check: points and polygons (vertex indices), as read.
struct PolygonSoup {
  Eigen::Matrix3Xd points;                 // m (after the scale factor)
  std::vector<std::vector<int>> polygons;  // vertex indices, any size ≥ 3
};

// The largest mesh file read: a 10-million-triangle binary STL is 500 MB.
inline constexpr std::uintmax_t kMaxMeshBytes = 1u << 30;  // 1 GiB

// The farthest a vertex may lie from the origin in any axis, m (after the scale): a particle is
// millimetres to metres across, and a volume (x^3) or inertia (x^5) of far larger coordinates
// overflows a double.
inline constexpr double kMaxCoordinate = 1e6;

struct ReadOptions {
  double scale = 1.0;  // multiplies every coordinate: 1e-3 for a mesh in millimetres
};

// Reads FILE by its extension (.stl, .obj, .ply, .off, any case): OFF and PLY with our own
// bounded readers (read_off.hpp, read_ply.hpp: every count checked against the bytes that follow
// before anything is allocated for it), STL and OBJ with CGAL's. Throws InputError
// "FILE: problem" for: a missing or empty file, an unknown extension, a truncated binary STL
// (declared against actual triangle count), content that does not parse as the format (with a
// hint when it looks like another format; OFF and PLY name the line, element or byte), NaN or
// infinite coordinates (with their count), coordinates beyond kMaxCoordinate, a polygon index
// out of range (OBJ: the line and the index), a file with no faces,
// and a scale that is not positive and finite; and before any reader runs: anything but a regular
// file and a file over kMaxMeshBytes.
PolygonSoup read_mesh_file(const std::filesystem::path& file, const ReadOptions& options = {});

}  // namespace asperity::geometry
