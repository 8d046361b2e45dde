# Rigid-sphere DEM: one Hertz pair, a 10,000-sphere packing under gravity, and whole runs of a
# bed of 100k and 1M spheres (set-up against steps, memory per sphere).
asperity_benchmark(bench_dem ${CMAKE_CURRENT_LIST_DIR}/dem_bench.cpp)
target_link_libraries(bench_dem PRIVATE asperity_run)
