# FEM/DEM core: internal-force kernel (tet updates/s), Munjiza contact kernel (pair evaluations/s),
# and whole particle-on-block collisions at 100–1000 surface triangles (with the geometry
# pipeline), for the benchmark's particle and for each particle of the generated set
# (`--set-particles=all`; `--scene-default` runs the set's collisions at what a scene that leaves
# the penalty to the solver gets, contact.max_contact_factor 2 by face-penalty, instead of α = 10
# as given; reports/fem/collision_cost.md), and the set-up alone of those worlds at 1000
# triangles (BM_CollisionSetup: make_world with the default's face-penalty limit and the critical
# step; reports/fem/mesh_step.md). The smoke test runs the first two particles of each: 21 s of
# CPU on the loaded machine, 6 s of it the two set-up benchmarks (meshing included).
asperity_benchmark(bench_fem ${CMAKE_CURRENT_LIST_DIR}/fem_bench.cpp)
target_link_libraries(bench_fem PRIVATE asperity_fdem)
target_link_libraries(bench_fem PRIVATE asperity_scenes)
if(TARGET asperity_geometry)
  target_link_libraries(bench_fem PRIVATE asperity_geometry)
  target_link_libraries(bench_fem PRIVATE asperity_io)
  # BM_CollisionSet reads the particle set (data/particles/set.json) from the source tree.
  target_compile_definitions(bench_fem PRIVATE ASPERITY_HAVE_GEOMETRY=1
                                               ASPERITY_SOURCE_DIR="${ASPERITY_SOURCE_DIR}")
endif()
# The statistics of those collisions over the set (medians, worst, exponents over N), computed by
# the C++ median and least-squares line (solver/core/) for collision_cost_table.py, which only
# reads them: build/bin/collision_cost RUNS.csv OUT_DIR.
add_executable(collision_cost ${CMAKE_CURRENT_LIST_DIR}/collision_cost.cpp)
target_link_libraries(collision_cost PRIVATE asperity_io asperity_warnings)
