// XML VTK writer (io/vtk_xml.hpp). Binary arrays go into one <AppendedData> block as base64,
// each as a UInt64 byte count followed by the values, the count and the values encoded
// separately, as VTK's own vtkXMLWriter does for uncompressed data; a DataArray's `offset` is the
// position of its block in the encoded characters after the leading '_'.
#include "io/vtk_xml.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <type_traits>

#include "io/atomic_file.hpp"

namespace asperity::io::vtk {
namespace {

constexpr std::uint8_t kVtkTetra = 10;  // VTK's cell type number of a linear tetrahedron

// Escapes what XML forbids in an attribute value (names come from scene files).
std::string xml_attribute(const std::string& s) {
  std::string out;
  for (const char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// Builds one document's arrays: the XML header of each, and the appended block or inline text.
class Document {
 public:
  explicit Document(Encoding e) : encoding_(e) {}

  template <class T>
  void array(std::ostringstream& xml, const char* type, const std::string& name, int components,
             const std::vector<T>& values) {
    xml << "<DataArray type=\"" << type << "\"";
    if (!name.empty()) xml << " Name=\"" << xml_attribute(name) << "\"";
    xml << " NumberOfComponents=\"" << components << "\"";
    if (encoding_ == Encoding::base64) {
      xml << " format=\"appended\" offset=\"" << appended_.size() << "\"/>\n";
      const std::uint64_t bytes = values.size() * sizeof(T);
      appended_ += base64(&bytes, sizeof bytes);
      appended_ += base64(values.data(), bytes);
      return;
    }
    xml << " format=\"ascii\">\n";
    char buf[32];
    for (std::size_t i = 0; i < values.size(); ++i) {
      if constexpr (std::is_floating_point_v<T>) {
        std::snprintf(buf, sizeof buf, "%.17g", values[i]);
      } else {
        std::snprintf(buf, sizeof buf, "%lld", static_cast<long long>(values[i]));
      }
      xml << buf << ((i + 1) % 9 == 0 || i + 1 == values.size() ? '\n' : ' ');
    }
    xml << "</DataArray>\n";
  }

  void fields(std::ostringstream& xml, const char* tag, const std::vector<DataArray>& data) {
    xml << "<" << tag << ">\n";
    for (const DataArray& a : data) {
      if (const auto* d = std::get_if<std::vector<double>>(&a.values)) {
        array(xml, "Float64", a.name, a.components, *d);
      } else {
        array(xml, "Int32", a.name, a.components, std::get<std::vector<std::int32_t>>(a.values));
      }
    }
    xml << "</" << tag << ">\n";
  }

  void points(std::ostringstream& xml, const Eigen::Matrix3Xd& x) {
    xml << "<Points>\n";
    array(xml, "Float64", "Points", 3, std::vector<double>(x.data(), x.data() + x.size()));
    xml << "</Points>\n";
  }

  // Closes the document: the appended block (if any) after the dataset.
  std::string finish(std::ostringstream& xml, const char* dataset) {
    xml << "</Piece>\n</" << dataset << ">\n";
    if (encoding_ == Encoding::base64) {
      xml << "<AppendedData encoding=\"base64\">\n_" << appended_ << "\n</AppendedData>\n";
    }
    xml << "</VTKFile>\n";
    return xml.str();
  }

  static void open(std::ostringstream& xml, const char* dataset) {
    xml << "<?xml version=\"1.0\"?>\n<VTKFile type=\"" << dataset
        << "\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n<" << dataset
        << ">\n";
  }

 private:
  Encoding encoding_;
  std::string appended_;
};

}  // namespace

std::string base64(const void* data, std::size_t n) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* p = static_cast<const unsigned char*>(data);
  std::string out;
  out.reserve((n + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 3 <= n; i += 3) {
    const std::uint32_t v =
        (std::uint32_t{p[i]} << 16) | (std::uint32_t{p[i + 1]} << 8) | std::uint32_t{p[i + 2]};
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += kAlphabet[(v >> 6) & 63];
    out += kAlphabet[v & 63];
  }
  if (const std::size_t rest = n - i; rest > 0) {
    const std::uint32_t v =
        (std::uint32_t{p[i]} << 16) | (rest == 2 ? std::uint32_t{p[i + 1]} << 8 : 0u);
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += rest == 2 ? kAlphabet[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

std::string unstructured_grid(const Eigen::Matrix3Xd& points, const Eigen::Matrix4Xi& tets,
                              const std::vector<DataArray>& point_data,
                              const std::vector<DataArray>& cell_data, Encoding encoding) {
  std::ostringstream xml;
  Document doc(encoding);
  Document::open(xml, "UnstructuredGrid");
  xml << "<Piece NumberOfPoints=\"" << points.cols() << "\" NumberOfCells=\"" << tets.cols()
      << "\">\n";
  doc.fields(xml, "PointData", point_data);
  doc.fields(xml, "CellData", cell_data);
  doc.points(xml, points);
  const std::vector<std::int32_t> connectivity(tets.data(), tets.data() + tets.size());
  std::vector<std::int32_t> offsets(static_cast<std::size_t>(tets.cols()));
  for (std::size_t k = 0; k < offsets.size(); ++k)
    offsets[k] = static_cast<std::int32_t>(4 * k + 4);
  const std::vector<std::uint8_t> types(offsets.size(), kVtkTetra);
  xml << "<Cells>\n";
  doc.array(xml, "Int32", "connectivity", 1, connectivity);
  doc.array(xml, "Int32", "offsets", 1, offsets);
  doc.array(xml, "UInt8", "types", 1, types);
  xml << "</Cells>\n";
  return doc.finish(xml, "UnstructuredGrid");
}

std::string point_cloud(const Eigen::Matrix3Xd& points, const std::vector<DataArray>& point_data,
                        Encoding encoding) {
  std::ostringstream xml;
  Document doc(encoding);
  Document::open(xml, "PolyData");
  xml << "<Piece NumberOfPoints=\"" << points.cols() << "\" NumberOfVerts=\"" << points.cols()
      << "\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n";
  doc.fields(xml, "PointData", point_data);
  doc.points(xml, points);
  std::vector<std::int32_t> connectivity(static_cast<std::size_t>(points.cols()));
  std::vector<std::int32_t> offsets(connectivity.size());
  for (std::size_t i = 0; i < connectivity.size(); ++i) {
    connectivity[i] = static_cast<std::int32_t>(i);
    offsets[i] = static_cast<std::int32_t>(i + 1);
  }
  xml << "<Verts>\n";
  doc.array(xml, "Int32", "connectivity", 1, connectivity);
  doc.array(xml, "Int32", "offsets", 1, offsets);
  xml << "</Verts>\n";
  return doc.finish(xml, "PolyData");
}

void Collection::add(double time, const std::string& file, int part) {
  const Entry e{.time = time, .part = part, .file = file};
  const auto at =
      std::upper_bound(entries_.begin(), entries_.end(), e, [](const Entry& a, const Entry& b) {
        return a.time < b.time || (a.time == b.time && a.part < b.part);
      });
  entries_.insert(at, e);
}

void Collection::write(const std::filesystem::path& pvd) const {
  std::ostringstream xml;
  xml << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\">\n<Collection>\n";
  char t[32];
  for (const Entry& e : entries_) {
    std::snprintf(t, sizeof t, "%.17g", e.time);
    xml << "<DataSet timestep=\"" << t << "\" part=\"" << e.part << "\" file=\""
        << xml_attribute(e.file) << "\"/>\n";
  }
  xml << "</Collection>\n</VTKFile>\n";
  write_atomically(pvd, xml.str());
}

}  // namespace asperity::io::vtk
