# Rigid polyhedra under the volume laws: the overlap kernel (clips/s), the narrow phase of a rock
# pressed into a block (one force evaluation, by surface triangles) and a whole rigid drop at
# 100–2000 triangles (with the geometry pipeline).
if(TARGET asperity_geometry)
  asperity_benchmark(bench_rigid ${CMAKE_CURRENT_LIST_DIR}/rigid_bench.cpp)
  target_link_libraries(bench_rigid PRIVATE asperity_fdem asperity_geometry)
  target_link_libraries(bench_rigid PRIVATE asperity_scenes)
  target_compile_definitions(bench_rigid PRIVATE ASPERITY_SOURCE_DIR="${ASPERITY_SOURCE_DIR}")
endif()
