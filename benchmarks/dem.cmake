# Rigid-sphere DEM: one Hertz pair, a 10,000-sphere packing under gravity, and whole runs of a
# bed of 100k and 1M spheres (set-up against steps, memory per sphere).
asperity_benchmark(bench_dem ${CMAKE_CURRENT_LIST_DIR}/dem_bench.cpp)
target_link_libraries(bench_dem PRIVATE asperity_run asperity_scenes)
# The performance record's command (tools/report/perf_table.py, docs/performance.md) on a small
# size: one pair, 64-sphere pressed and touching lattices, 20 steps, LAMMPS alone; BM_Packing10k
# run once. It fails when any code fails or a table cannot be written. About 10 s (CI: < 30 s).
add_test(NAME perf.smoke
         COMMAND /usr/bin/python3 ${ASPERITY_SOURCE_DIR}/tools/report/perf_table.py
                 ${CMAKE_BINARY_DIR} ${CMAKE_BINARY_DIR}/perf-smoke --smoke)
set_tests_properties(perf.smoke PROPERTIES LABELS perf-smoke TIMEOUT 120)
