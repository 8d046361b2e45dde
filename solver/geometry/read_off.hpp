// Reading OFF (Geomview's Object File Format, ASCII) into a polygon soup, bounded: every count is
// checked against the bytes that follow before anything is allocated for it.
#pragma once

#include <string>
#include <string_view>

#include "solver/geometry/read_mesh.hpp"

namespace asperity::geometry {

// Parses BYTES, the whole of FILE (named in the messages), as ASCII OFF: the keyword OFF with the
// optional prefixes ST, C, N and 4 (4OFF: homogeneous coordinates, divided by w), the counts
// "vertices faces [edges]", one vertex per line (extra values, normals, colours and texture
// coordinates, ignored), one face per line as "n i1 ... in" (a trailing colour ignored); '#'
// starts a comment. Returns the points as written (no scale). Throws InputError
// "FILE: OFF line L ...: problem" for: a missing keyword, binary OFF and nOFF (refused), counts
// that are not whole numbers below 2^40 or that the file's bytes cannot hold, a vertex with too
// few or unparsable coordinates, a face with fewer than 3 vertices or more than its line holds,
// a vertex index out of range, a file that ends early, and NaN or infinite coordinates (counted).
PolygonSoup read_off(const std::string& file, std::string_view bytes);

}  // namespace asperity::geometry
