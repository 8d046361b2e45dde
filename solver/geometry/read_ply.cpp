// Our own PLY reader. CGAL's (CGAL/IO/PLY.h) trusts its input: a property line before any element
// indexed an empty list, and a list count read from the data sized a buffer before the bytes were
// known to exist (UBSan "applying non-zero offset 18446744073709551552 to null pointer",
// fuzz_mesh_ply, CI of round 2), whatever the header had been pre-checked for. Here the header is
// parsed into a layout first, the layout's minimum size is checked against the bytes after the
// header, and every list count against the bytes left before anything is allocated for it.
// Format: Greg Turk's PLY description (http://paulbourke.net/dataformats/ply/).
#include "solver/geometry/read_ply.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "solver/core/error.hpp"
#include "solver/geometry/mesh_text.hpp"

namespace asperity::geometry {
namespace {

using text::shown;

// Counts above this are refused as absurd; with at most kMaxProperties properties of at most 8
// bytes per element, every count × size product stays below 2^63. At most kMaxElements elements
// (a mesh has two or three), so checking a name against those before it stays cheap.
constexpr std::int64_t kMaxCount = std::int64_t{1} << 40;
constexpr std::size_t kMaxProperties = 1000;
constexpr std::size_t kMaxElements = 100;

enum class Scalar { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };

std::optional<Scalar> scalar_type(std::string_view name) {
  struct Name {
    std::string_view a, b;
    Scalar type;
  };
  static constexpr Name kNames[] = {
      {"char", "int8", Scalar::kInt8},        {"uchar", "uint8", Scalar::kUint8},
      {"short", "int16", Scalar::kInt16},     {"ushort", "uint16", Scalar::kUint16},
      {"int", "int32", Scalar::kInt32},       {"uint", "uint32", Scalar::kUint32},
      {"float", "float32", Scalar::kFloat32}, {"double", "float64", Scalar::kFloat64}};
  for (const Name& n : kNames)
    if (name == n.a || name == n.b) return n.type;
  return std::nullopt;
}

std::int64_t bytes_of(Scalar t) {
  switch (t) {
    case Scalar::kInt8:
    case Scalar::kUint8:
      return 1;
    case Scalar::kInt16:
    case Scalar::kUint16:
      return 2;
    case Scalar::kInt32:
    case Scalar::kUint32:
    case Scalar::kFloat32:
      return 4;
    case Scalar::kFloat64:
      return 8;
  }
  return 8;
}

bool is_integer(Scalar t) {
  return t != Scalar::kFloat32 && t != Scalar::kFloat64;
}

struct Property {
  std::string name;
  Scalar type = Scalar::kFloat32;  // the item type of a list
  bool list = false;
  Scalar count_type = Scalar::kUint8;
};

struct Element {
  std::string name;
  std::int64_t count = 0;
  std::vector<Property> properties;
};

enum class Format { kAscii, kLittle, kBig };

class PlyReader {
 public:
  PlyReader(const std::string& file, std::string_view bytes) : file_(file), bytes_(bytes) {}

  PolygonSoup read() {
    header();
    check_layout();
    for (const Element& e : elements_) element(e);
    if (nonfinite_ > 0) {
      fail(std::to_string(nonfinite_) + " NaN or infinite coordinate values (PLY, the first in " +
           first_nonfinite_ + ")");
    }
    return std::move(soup_);
  }

 private:
  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError(file_ + ": " + problem);
  }
  [[noreturn]] void fail_header(std::size_t line, const std::string& problem) const {
    fail("PLY header line " + std::to_string(line) + ": " + problem);
  }

  // ------------------------------------------------------------------------------- header
  void header() {
    text::Lines lines(bytes_);
    std::string_view line;
    lines.next(line);
    if (line != "ply") {
      fail("not a valid PLY file: it does not start with the line \"ply\"" +
           text::wrong_extension_hint(bytes_, "PLY"));
    }
    bool has_format = false;
    while (true) {
      if (!lines.next(line)) fail("PLY header without end_header");
      const std::size_t n = lines.number();
      text::Tokens tokens(line);
      std::string_view kw;
      if (!tokens.next(kw) || kw == "comment" || kw == "obj_info") continue;
      if (kw == "end_header") break;
      std::string_view a, b, c, d;
      tokens.next(a);
      tokens.next(b);
      if (kw == "format") {
        if (a == "ascii") {
          format_ = Format::kAscii;
        } else if (a == "binary_little_endian") {
          format_ = Format::kLittle;
        } else if (a == "binary_big_endian") {
          format_ = Format::kBig;
        } else {
          fail_header(n, "unknown format " + shown(a) +
                             " (expected ascii, binary_little_endian or binary_big_endian)");
        }
        has_format = true;
      } else if (kw == "element") {
        const auto count = text::to_integer(b);
        if (a.empty() || !count || *count < 0 || *count >= kMaxCount) {
          fail_header(n, "element " + shown(a) +
                             ": the count must be a whole number below 2^40 (got " + shown(b) +
                             ")");
        }
        for (const Element& e : elements_)
          if (e.name == a) fail_header(n, "element " + shown(a) + " declared twice");
        if (elements_.size() == kMaxElements) {
          fail_header(n, "more than " + std::to_string(kMaxElements) + " elements");
        }
        elements_.push_back({std::string(a), *count, {}});
      } else if (kw == "property") {
        if (elements_.empty()) fail_header(n, "a property before any element");
        Element& e = elements_.back();
        if (e.properties.size() == kMaxProperties) {
          fail_header(n, "element " + shown(e.name) + " has more than " +
                             std::to_string(kMaxProperties) + " properties");
        }
        Property p;
        if (a == "list") {
          tokens.next(c);
          const auto ct = scalar_type(b), it = scalar_type(c);
          if (!ct || !is_integer(*ct)) {
            fail_header(n, "list count type " + shown(b) + " is not an integer type");
          }
          if (!it) fail_header(n, "unknown list item type " + shown(c));
          tokens.next(d);
          p = {std::string(d), *it, true, *ct};
        } else {
          const auto t = scalar_type(a);
          if (!t) fail_header(n, "unknown property type " + shown(a));
          p = {std::string(b), *t, false, Scalar::kUint8};
        }
        if (p.name.empty()) fail_header(n, "a property without a name");
        e.properties.push_back(std::move(p));
      } else {
        fail_header(n, "unknown keyword " + shown(kw));
      }
    }
    if (!has_format) fail("PLY header without a format line");
    data_ = lines.rest();
    data_line_ = lines.number() + 1;
  }

  // The vertex and face elements give what the soup needs; their layout is checked here, and
  // the least size of every element against the bytes after the header.
  void check_layout() {
    std::int64_t nf = 0;
    for (const Element& e : elements_) {
      if (e.name == "vertex") {
        nv_ = e.count;
        for (const char* axis : {"x", "y", "z"}) {
          const Property* p = find(e, axis);
          if (!p || p->list) {
            fail("PLY element \"vertex\" has no scalar property " + std::string(axis));
          }
        }
      } else if (e.name == "face") {
        nf = e.count;
        const Property* p = face_list(e);
        if (!p) {
          fail("PLY element \"face\" has no list property vertex_indices (or vertex_index)");
        }
        if (!is_integer(p->type)) {
          fail("PLY face list " + shown(p->name) + ": the index type is not an integer type");
        }
      }
    }
    std::int64_t need = 0;
    const auto left = static_cast<std::int64_t>(data_.size());
    for (const Element& e : elements_) {
      std::int64_t least = 0;  // bytes per item: 2 per ASCII number, a list's count in binary
      for (const Property& p : e.properties) {
        least += format_ == Format::kAscii ? 2 : bytes_of(p.list ? p.count_type : p.type);
      }
      need += e.count * least;  // below 2^40 × 8000 each; stops growing once it passes LEFT
      if (need > left) {
        fail("PLY header declares " + std::to_string(nv_) + " vertices and " + std::to_string(nf) +
             " faces, which need at least " + std::to_string(need) + " bytes (up to element " +
             shown(e.name) + "); " + std::to_string(left) + " follow the header");
      }
    }
    soup_.points.resize(3, static_cast<Eigen::Index>(nv_));
    soup_.points.setZero();
    soup_.polygons.reserve(static_cast<std::size_t>(nf));
  }

  static const Property* find(const Element& e, std::string_view name) {
    for (const Property& p : e.properties)
      if (p.name == name) return &p;
    return nullptr;
  }
  static const Property* face_list(const Element& e) {
    for (const Property& p : e.properties)
      if (p.list && (p.name == "vertex_indices" || p.name == "vertex_index")) return &p;
    return nullptr;
  }

  // --------------------------------------------------------------------------------- data
  // Where the reader is, for a message: the element, its item, and the line or byte offset.
  std::string where(const Element& e, std::int64_t item) const {
    std::string s = "PLY element " + shown(e.name) + " " + std::to_string(item);
    if (format_ == Format::kAscii) return s + " (line " + std::to_string(tokens_.line()) + ")";
    return s + " (byte " + std::to_string(bytes_.size() - data_.size() + pos_) + ")";
  }

  std::size_t bytes_left() const {
    return format_ == Format::kAscii ? tokens_.bytes_left() : data_.size() - pos_;
  }

  // One scalar of type T from the data, as a double (exact for every integer type of PLY).
  double scalar(Scalar t, const Element& e, std::int64_t item) {
    if (format_ == Format::kAscii) {
      std::string_view token;
      if (!tokens_.next(token)) fail(where(e, item) + ": the file ends early");
      const auto x = text::to_double(token);
      if (!x) fail(where(e, item) + ": " + shown(token) + " is not a number");
      return *x;
    }
    const auto n = static_cast<std::size_t>(bytes_of(t));
    if (data_.size() - pos_ < n) fail(where(e, item) + ": the file ends early");
    unsigned char b[8];
    std::memcpy(b, data_.data() + pos_, n);
    pos_ += n;
    const bool swap = (format_ == Format::kLittle) != (std::endian::native == std::endian::little);
    if (swap)
      for (std::size_t i = 0; i < n / 2; ++i) std::swap(b[i], b[n - 1 - i]);
    switch (t) {
      case Scalar::kInt8:
        return static_cast<double>(static_cast<std::int8_t>(b[0]));
      case Scalar::kUint8:
        return b[0];
      case Scalar::kInt16:
        return static_cast<double>(load<std::int16_t>(b));
      case Scalar::kUint16:
        return static_cast<double>(load<std::uint16_t>(b));
      case Scalar::kInt32:
        return static_cast<double>(load<std::int32_t>(b));
      case Scalar::kUint32:
        return static_cast<double>(load<std::uint32_t>(b));
      case Scalar::kFloat32:
        return static_cast<double>(load<float>(b));
      case Scalar::kFloat64:
        return load<double>(b);
    }
    return 0;
  }
  template <class T>
  static T load(const unsigned char* b) {
    T x;
    std::memcpy(&x, b, sizeof x);
    return x;
  }

  // A list count or an index: a whole number (in ASCII, a token without fraction).
  std::int64_t integer(Scalar t, const Element& e, std::int64_t item, const char* what) {
    if (format_ == Format::kAscii) {
      std::string_view token;
      if (!tokens_.next(token)) fail(where(e, item) + ": the file ends early");
      const auto x = text::to_integer(token);
      if (!x) fail(where(e, item) + ": " + what + " " + shown(token) + " is not a whole number");
      return *x;
    }
    return static_cast<std::int64_t>(scalar(t, e, item));  // exact: integer types only
  }

  void element(const Element& e) {
    // An element without properties takes no bytes whatever its count (up to 2^40): looping over
    // its items read nothing and took minutes (fuzz_mesh_ply's one-hour run: a timeout).
    if (e.properties.empty()) return;
    if (format_ == Format::kAscii && !ascii_started_) {
      tokens_ = text::Tokens(data_, data_line_);
      ascii_started_ = true;
    }
    const bool vertex = e.name == "vertex", face = e.name == "face";
    const Property* list = face ? face_list(e) : nullptr;
    for (std::int64_t item = 0; item < e.count; ++item) {
      for (const Property& p : e.properties) {
        if (!p.list) {
          const double x = scalar(p.type, e, item);
          if (!vertex) continue;
          const int axis = p.name == "x" ? 0 : p.name == "y" ? 1 : p.name == "z" ? 2 : -1;
          if (axis < 0) continue;
          if (!std::isfinite(x) && nonfinite_++ == 0) first_nonfinite_ = where(e, item);
          soup_.points(axis, static_cast<Eigen::Index>(item)) = x;
          continue;
        }
        const std::int64_t n = integer(p.count_type, e, item, "list count");
        // Each item takes at least 2 bytes in ASCII (a digit and a separator), its size in binary.
        const std::int64_t least = format_ == Format::kAscii ? 2 : bytes_of(p.type);
        if (n < 0 || n > static_cast<std::int64_t>(bytes_left()) / least) {
          fail(where(e, item) + ": list " + shown(p.name) + " declares " + std::to_string(n) +
               " items; " + std::to_string(bytes_left()) + " bytes are left");
        }
        if (&p != list) {
          for (std::int64_t i = 0; i < n; ++i) scalar(p.type, e, item);
          continue;
        }
        if (n < 3) {
          fail(where(e, item) + ": " + std::to_string(n) + " vertices; a face needs at least 3");
        }
        std::vector<int> polygon;
        polygon.reserve(static_cast<std::size_t>(n));
        for (std::int64_t i = 0; i < n; ++i) {
          const std::int64_t v = integer(p.type, e, item, "vertex index");
          if (v < 0 || v >= nv_) {
            fail(where(e, item) + ": vertex index " + std::to_string(v) +
                 " out of range (the header declares " + std::to_string(nv_) + " vertices)");
          }
          polygon.push_back(static_cast<int>(v));
        }
        soup_.polygons.push_back(std::move(polygon));
      }
    }
  }

  const std::string& file_;
  std::string_view bytes_;
  Format format_ = Format::kAscii;
  std::vector<Element> elements_;
  std::string_view data_;  // the bytes after end_header
  std::size_t data_line_ = 1;
  std::size_t pos_ = 0;  // binary: the offset in data_
  text::Tokens tokens_{std::string_view()};
  bool ascii_started_ = false;
  std::int64_t nv_ = 0;
  std::size_t nonfinite_ = 0;
  std::string first_nonfinite_;
  PolygonSoup soup_;
};

}  // namespace

PolygonSoup read_ply(const std::string& file, std::string_view bytes) {
  return PlyReader(file, bytes).read();
}

}  // namespace asperity::geometry
