# Rigid polyhedra under the volume laws: the overlap kernel (clips/s), the narrow phase of a rock
# pressed into a block (one force evaluation, by surface triangles) and a whole rigid drop at
# 100–2000 triangles (with the geometry pipeline).
if(TARGET asperity_geometry)
  # The smoke runs every benchmark but the broad phase on the 1000- and 2000-vertex hulls: their
  # set-up (the geometry pipeline's TetGen passes and lifting on long, flat hull tetrahedra) took
  # 12 and 54 s of the smoke's 72 s on the development machine (102 s in a fresh-clone .ci/run there), for 0.08 and 0.18 ms
  # of the measured call; the 50- and 250-vertex hulls run the same code.
  set(bench_rigid_SMOKE_FILTER
      "^(BM_OverlapKernel|BM_NarrowPhase/.*|BM_BroadPhaseHull/(50|250)|BM_RigidDrop/.*)$")
  asperity_benchmark(bench_rigid ${CMAKE_CURRENT_LIST_DIR}/rigid_bench.cpp)
  target_link_libraries(bench_rigid PRIVATE asperity_fdem asperity_geometry)
  target_link_libraries(bench_rigid PRIVATE asperity_scenes)
  target_compile_definitions(bench_rigid PRIVATE ASPERITY_SOURCE_DIR="${ASPERITY_SOURCE_DIR}")
endif()
