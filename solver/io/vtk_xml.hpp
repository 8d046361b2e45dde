// ParaView's XML formats, written from plain arrays: an unstructured grid of tetrahedra (.vtu),
// a cloud of points (.vtp) and the time-series collection that lists them (.pvd). The layout
// follows Kitware's "VTK File Formats" (VTK User's Guide, ch. 19, XML file formats).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <variant>
#include <vector>

#include <Eigen/Core>

namespace asperity::io::vtk {

// Appended base64 (compact and exact: the doubles round-trip bit for bit) or inline ASCII
// (readable; written with 17 significant digits, so it round-trips too, at about 2.3× the size).
enum class Encoding { base64, ascii };

// The values of an array already encoded (base64 of its byte count and values, or its ASCII
// text): what does not change between the frames of a series (cells, body ids) is encoded once
// and copied into every document.
struct Encoded {
  const char* type = "Int32";  // VTK's type name: Float64, Int32, UInt8
  Encoding encoding = Encoding::base64;
  std::size_t count = 0;  // values
  std::string text;
};

// One named field: `components` values per point or cell, row-major (point 0's x y z, then
// point 1's ...).
struct DataArray {
  std::string name;
  int components = 1;
  std::variant<std::vector<double>, std::vector<std::int32_t>, Encoded> values;
};

// The same array with its values encoded once for `encoding` (the documents it goes into must
// use the same encoding).
DataArray encoded(const DataArray& a, Encoding encoding);

// The cells of a tetrahedral grid, encoded once: a series' frames share them.
struct TetCells {
  Eigen::Index count = 0;
  Encoded connectivity, offsets, types;
};
TetCells tet_cells(const Eigen::Matrix4Xi& tets, Encoding encoding);

// A .vtu document: every column of `tets` is one linear tetrahedron (VTK_TETRA) over `points`.
std::string unstructured_grid(const Eigen::Matrix3Xd& points, const Eigen::Matrix4Xi& tets,
                              const std::vector<DataArray>& point_data,
                              const std::vector<DataArray>& cell_data, Encoding encoding);
// The same document from cells encoded once (tet_cells with the same encoding): byte for byte
// what the overload above writes.
std::string unstructured_grid(const Eigen::Matrix3Xd& points, const TetCells& cells,
                              const std::vector<DataArray>& point_data,
                              const std::vector<DataArray>& cell_data, Encoding encoding);

// A .vtp document: every point is one vertex cell, so ParaView's Glyph filter (sphere glyphs
// scaled by "radius") draws spheres.
std::string point_cloud(const Eigen::Matrix3Xd& points, const std::vector<DataArray>& point_data,
                        Encoding encoding);

// The .pvd collection of a time series. `write` replaces the file atomically and lists only
// entries already added, so the caller adds a frame after its files are complete: a run killed
// between two frames leaves a collection of whole frames only.
class Collection {
 public:
  // `file` is relative to the collection's folder; `part` tells apart several datasets of one
  // time step (ParaView shows them as blocks of one multiblock).
  void add(double time, const std::string& file, int part);
  void write(const std::filesystem::path& pvd) const;
  std::size_t size() const { return entries_.size(); }

 private:
  struct Entry {
    double time;
    int part;
    std::string file;
  };
  std::vector<Entry> entries_;  // kept sorted by time, then part
};

// RFC 4648 base64 of `n` bytes (exposed for the tests).
std::string base64(const void* data, std::size_t n);
// The same, appended to `out`.
void append_base64(std::string& out, const void* data, std::size_t n);

}  // namespace asperity::io::vtk
