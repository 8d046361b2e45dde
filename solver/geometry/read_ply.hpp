// Reading PLY (Stanford polygon file format: ascii, binary_little_endian, binary_big_endian) into
// a polygon soup, bounded: every count is checked against the bytes that follow before anything
// is allocated for it.
#pragma once

#include <string>
#include <string_view>

#include "solver/geometry/read_mesh.hpp"

namespace asperity::geometry {

// Parses BYTES, the whole of FILE (named in the messages), as PLY. The header holds "format",
// "comment", "obj_info", "element NAME COUNT" and "property TYPE NAME" / "property list
// COUNT-TYPE ITEM-TYPE NAME" lines up to "end_header", with the types char, uchar, short, ushort,
// int, uint, float, double and their sized names (int8 ... float64). Element "vertex" gives
// the scalar properties x, y, z (any type); element "face" the list vertex_indices (or
// vertex_index) of integer count and index types; every other property and element is skipped
// by its declared layout. Returns the points as written (no scale). Throws InputError
// "FILE: PLY ...: problem" naming the header line, or the element, its item and the line (ASCII)
// or byte offset (binary), for: a malformed header, counts the remaining bytes cannot hold, a
// list count that is negative or larger than the bytes left, a face with fewer than 3 vertices,
// a vertex index out of range, data that ends early or does not parse, and NaN or infinite
// coordinates (counted).
PolygonSoup read_ply(const std::string& file, std::string_view bytes);

}  // namespace asperity::geometry
