# Rigid-sphere DEM: one Hertz pair, and a 10,000-sphere packing under gravity.
asperity_benchmark(bench_dem ${CMAKE_CURRENT_LIST_DIR}/dem_bench.cpp)
target_link_libraries(bench_dem PRIVATE asperity_dem)
