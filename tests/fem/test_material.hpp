// The material every fem test builds its elements of (one definition: the test files of
// fem_tests compile as one translation unit, tests/CMakeLists.txt).
#pragma once

namespace asperity::fem::test_material {

inline constexpr double kE = 1e9;     // Young's modulus, Pa: a stiff rock-like solid
inline constexpr double kNu = 0.3;    // Poisson's ratio
inline constexpr double kRho = 2000;  // density, kg/m³

}  // namespace asperity::fem::test_material
