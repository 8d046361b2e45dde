// Every key the scene loader accepts, by the object it sits in. The loader rejects any other key
// against these tables (scene/load_scene.cpp), and a test checks that docs/scenes.md documents
// each one under its full path (tests/scene/test_scene_keys.cpp).
#pragma once

#include <span>
#include <string_view>

namespace asperity::scene::keys {

inline constexpr std::string_view kScene[] = {"name",
                                              "gravity",
                                              "duration",
                                              "dt",
                                              "dt_safety",
                                              "allow_unsafe_dt",
                                              "unstable_energy_growth",
                                              "allow_initial_overlap",
                                              "materials",
                                              "bodies",
                                              "contact",
                                              "record",
                                              "output"};
inline constexpr std::string_view kMaterial[] = {"density",  "young",       "poisson",
                                                 "friction", "restitution", "law"};
inline constexpr std::string_view kBody[] = {
    "name",     "material",         "shape", "model",        "position",
    "velocity", "angular_velocity", "fixed", "damping_ratio"};
inline constexpr std::string_view kSphere[] = {"type", "radius"};
inline constexpr std::string_view kPlane[] = {"type", "point", "normal"};
inline constexpr std::string_view kBox[] = {"type", "min", "max"};
inline constexpr std::string_view kMesh[] = {"type",
                                             "file",
                                             "faces",
                                             "scale",
                                             "element_size",
                                             "element_size_focus",
                                             "element_size_focus_radius",
                                             "element_size_growth",
                                             "element_size_far"};
inline constexpr std::string_view kContact[] = {"law",
                                                "kn",
                                                "kt",
                                                "penalty",
                                                "penalty_alpha",
                                                "max_contact_factor",
                                                "contact_factor_by",
                                                "max_added_mass",
                                                "kv",
                                                "friction",
                                                "restitution"};
inline constexpr std::string_view kRecord[] = {"force_on", "every", "end_after_separation"};
inline constexpr std::string_view kOutput[] = {"vtk_every", "vtk_format"};

// Each table with the path docs/scenes.md writes before its keys (`bodies[].shape.radius`).
struct Table {
  std::string_view prefix;
  std::span<const std::string_view> keys;
};
inline constexpr Table kTables[] = {{"", kScene},
                                    {"materials.NAME.", kMaterial},
                                    {"bodies[].", kBody},
                                    {"bodies[].shape.", kSphere},
                                    {"bodies[].shape.", kPlane},
                                    {"bodies[].shape.", kBox},
                                    {"bodies[].shape.", kMesh},
                                    {"contact.", kContact},
                                    {"record.", kRecord},
                                    {"output.", kOutput}};

}  // namespace asperity::scene::keys
