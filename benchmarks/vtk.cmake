# ParaView frames: the cost of writing them every N steps of a 1000-triangle collision, and their
# size (needs the geometry pipeline for the particle).
if(TARGET asperity_geometry)
  asperity_benchmark(bench_vtk ${CMAKE_CURRENT_LIST_DIR}/vtk_bench.cpp)
  target_link_libraries(bench_vtk PRIVATE asperity_run asperity_geometry)
endif()
