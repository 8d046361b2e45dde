# Geometry pipeline: a ~60k-triangle generated particle simplified to 1000 triangles, then
# tetrahedralized keeping them (issue 3 target: under 1 s together on one core).
asperity_benchmark(bench_geometry ${CMAKE_CURRENT_LIST_DIR}/geometry_bench.cpp)
target_link_libraries(bench_geometry PRIVATE asperity_geometry)
