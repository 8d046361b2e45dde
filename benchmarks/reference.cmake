# The finite-sphere reference (validation/reference/): the cost of fitting its law (assembly,
# factorisation, condensation, the states) per mesh level, and of an impact from the cached law.
asperity_benchmark(bench_reference ${CMAKE_CURRENT_LIST_DIR}/reference_bench.cpp)
target_link_libraries(bench_reference PRIVATE asperity_reference)
