// XML VTK writer (io/vtk_xml.hpp). Binary arrays go into one <AppendedData> block as base64,
// each as a UInt64 byte count followed by the values, the count and the values encoded
// separately, as VTK's own vtkXMLWriter does for uncompressed data; a DataArray's `offset` is the
// position of its block in the encoded characters after the leading '_'. Because each array's
// block stands alone, an array encoded once (Encoded) is copied into any document as it is.
#include "solver/io/vtk_xml.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include "solver/io/atomic_file.hpp"

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

template <class T>
constexpr const char* vtk_type() {
  if constexpr (std::is_same_v<T, double>) return "Float64";
  if constexpr (std::is_same_v<T, std::int32_t>) return "Int32";
  if constexpr (std::is_same_v<T, std::uint8_t>) return "UInt8";
}

// Appends `n` values: base64 of their UInt64 byte count, then of the values (encoded separately,
// as VTK's own writer does); or ASCII, nine to a line, doubles with 17 significant digits.
template <class T>
void encode_values(std::string& out, const T* v, std::size_t n, Encoding encoding) {
  if (encoding == Encoding::base64) {
    const std::uint64_t bytes = n * sizeof(T);
    append_base64(out, &bytes, sizeof bytes);
    append_base64(out, v, bytes);
    return;
  }
  char buf[32];
  for (std::size_t i = 0; i < n; ++i) {
    int len = 0;
    if constexpr (std::is_floating_point_v<T>) {
      len = std::snprintf(buf, sizeof buf, "%.17g", v[i]);
    } else {
      len = std::snprintf(buf, sizeof buf, "%lld", static_cast<long long>(v[i]));
    }
    out.append(buf, static_cast<std::size_t>(len));
    out += (i + 1) % 9 == 0 || i + 1 == n ? '\n' : ' ';
  }
}

template <class T>
Encoded encode(const T* v, std::size_t n, Encoding encoding) {
  Encoded e{.type = vtk_type<T>(), .encoding = encoding, .count = n, .text = {}};
  encode_values(e.text, v, n, encoding);
  return e;
}

// Base64 characters of `bytes` bytes of values with their count (what encode_values appends).
std::size_t base64_size(std::size_t bytes) {
  return (sizeof(std::uint64_t) + 2) / 3 * 4 + (bytes + 2) / 3 * 4;
}

std::size_t value_bytes(const DataArray& a) {
  return std::visit(
      [](const auto& v) -> std::size_t {
        if constexpr (std::is_same_v<std::decay_t<decltype(v)>, Encoded>) {
          return v.text.size() * 3 / 4;
        } else {
          return v.size() * sizeof(v[0]);
        }
      },
      a.values);
}

// Builds one document in two strings: the XML, and the appended block (base64) that follows it.
// Plain strings, sized up front: a frame is a few hundred kilobytes written many times a run.
class Document {
 public:
  Document(Encoding e, const char* dataset, std::size_t appended_chars)
      : encoding_(e), dataset_(dataset) {
    xml_.reserve(4096);
    if (e == Encoding::base64) appended_.reserve(appended_chars);
    xml_ += "<?xml version=\"1.0\"?>\n<VTKFile type=\"";
    xml_ += dataset;
    xml_ += "\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n<";
    xml_ += dataset;
    xml_ += ">\n";
  }

  std::string& xml() { return xml_; }

  template <class T>
  void array(const std::string& name, int components, const T* values, std::size_t n) {
    header(vtk_type<T>(), name, components);
    if (encoding_ == Encoding::base64) {
      encode_values(appended_, values, n, encoding_);
      return;
    }
    encode_values(xml_, values, n, encoding_);
    xml_ += "</DataArray>\n";
  }

  void array(const std::string& name, int components, const Encoded& e) {
    if (e.encoding != encoding_)
      throw std::logic_error("vtk: " + name + " encoded for another encoding");
    header(e.type, name, components);
    if (encoding_ == Encoding::base64) {
      appended_ += e.text;
      return;
    }
    xml_ += e.text;
    xml_ += "</DataArray>\n";
  }

  void fields(const char* tag, const std::vector<DataArray>& data) {
    xml_ += '<';
    xml_ += tag;
    xml_ += ">\n";
    for (const DataArray& a : data) {
      std::visit(
          [&](const auto& v) {
            if constexpr (std::is_same_v<std::decay_t<decltype(v)>, Encoded>) {
              array(a.name, a.components, v);
            } else {
              array(a.name, a.components, v.data(), v.size());
            }
          },
          a.values);
    }
    xml_ += "</";
    xml_ += tag;
    xml_ += ">\n";
  }

  void points(const Eigen::Matrix3Xd& x) {
    xml_ += "<Points>\n";
    array("Points", 3, x.data(), static_cast<std::size_t>(x.size()));
    xml_ += "</Points>\n";
  }

  // Closes the document: the appended block (if any) after the dataset.
  std::string finish() {
    xml_ += "</Piece>\n</";
    xml_ += dataset_;
    xml_ += ">\n";
    if (encoding_ == Encoding::base64) {
      xml_.reserve(xml_.size() + appended_.size() + 64);
      xml_ += "<AppendedData encoding=\"base64\">\n_";
      xml_ += appended_;
      xml_ += "\n</AppendedData>\n";
    }
    xml_ += "</VTKFile>\n";
    return std::move(xml_);
  }

 private:
  void header(const char* type, const std::string& name, int components) {
    xml_ += "<DataArray type=\"";
    xml_ += type;
    xml_ += '"';
    if (!name.empty()) {
      xml_ += " Name=\"";
      xml_ += xml_attribute(name);
      xml_ += '"';
    }
    xml_ += " NumberOfComponents=\"";
    xml_ += std::to_string(components);
    xml_ += '"';
    if (encoding_ == Encoding::base64) {
      xml_ += " format=\"appended\" offset=\"";
      xml_ += std::to_string(appended_.size());
      xml_ += "\"/>\n";
    } else {
      xml_ += " format=\"ascii\">\n";
    }
  }

  Encoding encoding_;
  const char* dataset_;
  std::string xml_;
  std::string appended_;
};

}  // namespace

std::string base64(const void* data, std::size_t n) {
  std::string out;
  append_base64(out, data, n);
  return out;
}

void append_base64(std::string& out, const void* data, std::size_t n) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* p = static_cast<const unsigned char*>(data);
  const std::size_t at = out.size();
  out.resize(at + (n + 2) / 3 * 4);
  char* o = out.data() + at;
  std::size_t i = 0;
  for (; i + 3 <= n; i += 3, o += 4) {
    const std::uint32_t v =
        (std::uint32_t{p[i]} << 16) | (std::uint32_t{p[i + 1]} << 8) | std::uint32_t{p[i + 2]};
    o[0] = kAlphabet[(v >> 18) & 63];
    o[1] = kAlphabet[(v >> 12) & 63];
    o[2] = kAlphabet[(v >> 6) & 63];
    o[3] = kAlphabet[v & 63];
  }
  if (const std::size_t rest = n - i; rest > 0) {
    const std::uint32_t v =
        (std::uint32_t{p[i]} << 16) | (rest == 2 ? std::uint32_t{p[i + 1]} << 8 : 0u);
    o[0] = kAlphabet[(v >> 18) & 63];
    o[1] = kAlphabet[(v >> 12) & 63];
    o[2] = rest == 2 ? kAlphabet[(v >> 6) & 63] : '=';
    o[3] = '=';
  }
}

DataArray encoded(const DataArray& a, Encoding encoding) {
  DataArray out{.name = a.name, .components = a.components, .values = {}};
  std::visit(
      [&](const auto& v) {
        if constexpr (std::is_same_v<std::decay_t<decltype(v)>, Encoded>) {
          out.values = v;
        } else {
          out.values = encode(v.data(), v.size(), encoding);
        }
      },
      a.values);
  return out;
}

TetCells tet_cells(const Eigen::Matrix4Xi& tets, Encoding encoding) {
  static_assert(sizeof(int) == sizeof(std::int32_t));
  const auto n = static_cast<std::size_t>(tets.cols());
  std::vector<std::int32_t> offsets(n);
  for (std::size_t k = 0; k < n; ++k) offsets[k] = static_cast<std::int32_t>(4 * k + 4);
  const std::vector<std::uint8_t> types(n, kVtkTetra);
  return {.count = tets.cols(),
          .connectivity = encode(reinterpret_cast<const std::int32_t*>(tets.data()),
                                 static_cast<std::size_t>(tets.size()), encoding),
          .offsets = encode(offsets.data(), n, encoding),
          .types = encode(types.data(), n, encoding)};
}

std::string unstructured_grid(const Eigen::Matrix3Xd& points, const Eigen::Matrix4Xi& tets,
                              const std::vector<DataArray>& point_data,
                              const std::vector<DataArray>& cell_data, Encoding encoding) {
  return unstructured_grid(points, tet_cells(tets, encoding), point_data, cell_data, encoding);
}

std::string unstructured_grid(const Eigen::Matrix3Xd& points, const TetCells& cells,
                              const std::vector<DataArray>& point_data,
                              const std::vector<DataArray>& cell_data, Encoding encoding) {
  std::size_t chars = base64_size(static_cast<std::size_t>(points.size()) * sizeof(double)) +
                      cells.connectivity.text.size() + cells.offsets.text.size() +
                      cells.types.text.size();
  for (const auto* data : {&point_data, &cell_data}) {
    for (const DataArray& a : *data) chars += base64_size(value_bytes(a));
  }
  Document doc(encoding, "UnstructuredGrid", chars);
  std::string& xml = doc.xml();
  xml += "<Piece NumberOfPoints=\"" + std::to_string(points.cols()) + "\" NumberOfCells=\"" +
         std::to_string(cells.count) + "\">\n";
  doc.fields("PointData", point_data);
  doc.fields("CellData", cell_data);
  doc.points(points);
  xml += "<Cells>\n";
  doc.array("connectivity", 1, cells.connectivity);
  doc.array("offsets", 1, cells.offsets);
  doc.array("types", 1, cells.types);
  xml += "</Cells>\n";
  return doc.finish();
}

std::string point_cloud(const Eigen::Matrix3Xd& points, const std::vector<DataArray>& point_data,
                        Encoding encoding) {
  const auto n = static_cast<std::size_t>(points.cols());
  std::size_t chars = base64_size(3 * n * sizeof(double)) + 2 * base64_size(n * 4);
  for (const DataArray& a : point_data) chars += base64_size(value_bytes(a));
  Document doc(encoding, "PolyData", chars);
  doc.xml() += "<Piece NumberOfPoints=\"" + std::to_string(n) + "\" NumberOfVerts=\"" +
               std::to_string(n) +
               "\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n";
  doc.fields("PointData", point_data);
  doc.points(points);
  std::vector<std::int32_t> connectivity(n), offsets(n);
  for (std::size_t i = 0; i < n; ++i) {
    connectivity[i] = static_cast<std::int32_t>(i);
    offsets[i] = static_cast<std::int32_t>(i + 1);
  }
  doc.xml() += "<Verts>\n";
  doc.array("connectivity", 1, connectivity.data(), n);
  doc.array("offsets", 1, offsets.data(), n);
  doc.xml() += "</Verts>\n";
  return doc.finish();
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
