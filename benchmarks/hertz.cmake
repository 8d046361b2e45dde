# The Hertz convergence levels (issue 11, item 2): one deformable-sphere impact per benchmark, on
# a fixed block or head-on with its mirror image, by contact size a/R and refinement s, graded or
# uniform; CPU seconds of the run per impact, with the errors against Hertz as counters.
# reports/fem/hertz_convergence.md is made from its JSON output by hertz_convergence_table.py.
# The smoke test runs only the cheapest level (block, a/R = 0.15, s = 2: 14–16 s of run CPU, 36 s
# wall on the loaded machine). Run the rest by --benchmark_filter: the report's levels took about
# 40 min of CPU; the whole registered set (the pair at every a/R, s = 1 at a/R = 0.05) would take
# hours.
if(TARGET asperity_geometry)
  add_executable(bench_hertz ${CMAKE_CURRENT_LIST_DIR}/hertz_bench.cpp)
  target_link_libraries(bench_hertz PRIVATE benchmark::benchmark asperity_warnings asperity_fdem
                        asperity_geometry)
  target_link_libraries(bench_hertz PRIVATE asperity_scenes)
  add_test(NAME bench_hertz_smoke
           COMMAND bench_hertz --benchmark_filter=^HertzBlock/graded/aR:0.150/s:2.000/)
  set_tests_properties(bench_hertz_smoke PROPERTIES LABELS benchmark)
endif()
# The Richardson columns of that table (order, the finest level's own error, the limit) and the
# least-squares lines of its limits against a/R, computed by the C++ rules
# (solver/core/richardson.hpp, least_squares.hpp) for hertz_convergence_table.py, which only reads
# them: build/bin/hertz_rates < "coarse middle fine ratio" lines (--line: "x1 y1 x2 y2 ..." lines).
add_executable(hertz_rates ${CMAKE_CURRENT_LIST_DIR}/hertz_rates.cpp)
target_link_libraries(hertz_rates PRIVATE asperity_core asperity_warnings)
