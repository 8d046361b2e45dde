// Writing surfaces and tetrahedral meshes, each file atomically (temporary file, then rename),
// so an interrupted run never leaves a half-written file that looks complete.
#pragma once

#include <filesystem>

#include "solver/core/mesh.hpp"
#include "solver/io/atomic_file.hpp"

namespace asperity::geometry {

// Every file below goes through io::write_atomically (FILE.partial-PID, then a rename).
using io::write_atomically;

// By extension: .off, .obj, .ply (ASCII) with 17 significant digits (doubles round-trip
// exactly), or .stl (binary, 32-bit floats as the format has). InputError for any other.
void write_surface_mesh(const std::filesystem::path& file, const SurfaceMesh& mesh);

// Legacy VTK unstructured grid (ASCII), cell type 10 (VTK_TETRA): opens in ParaView.
void write_vtk_tets(const std::filesystem::path& file, const TetMesh& mesh);

}  // namespace asperity::geometry
