# Writes OUT, the peers' gates as tests (validation/gates/CMakeLists.txt includes it into ctest),
# from `ASPERITY crosscheck --list --peer PEERS` (validation/peer_policy.json decides; this script
# only loops). A polyhedra gate runs the cross-check, then CHECK_POLYHEDRA on its comparison.json.
# Usage: cmake -DASPERITY=... -DPEERS=yade,lammps,liggghts -DCASES=DIR -DBINARY_DIR=DIR
# -DCHECK_POLYHEDRA=check_polyhedra_crosscheck.py -DOUT=FILE -P peer_gates.cmake
execute_process(COMMAND ${ASPERITY} crosscheck --list --peer ${PEERS} --cases ${CASES}
                OUTPUT_VARIABLE text ERROR_VARIABLE error RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "asperity crosscheck --list failed (${status}): ${error}")
endif()
# One list element per line; a ';' inside a line (a reason's) must not split it.
string(REPLACE ";" "<semicolon>" text "${text}")
string(REPLACE "\n" ";" lines "${text}")
set(tests "# Written by peer_gates.cmake from `asperity crosscheck --list`: do not edit.\n")
foreach(line IN LISTS lines)
  if(line MATCHES "^# ([^:]+):")
    set(peer ${CMAKE_MATCH_1})  # each peer's lines follow its header line
    continue()
  endif()
  if(line STREQUAL "")
    continue()
  endif()
  if(NOT line MATCHES "^(run|refused|polyhedra)\t([^\t]+)\t([^\t]+)\t([^\t]+)\t([^\t]+)\t")
    message(FATAL_ERROR "asperity crosscheck --list: a line it should not print: ${line}")
  endif()
  set(kind ${CMAKE_MATCH_1})
  set(case_name ${CMAKE_MATCH_2})
  set(case_file ${CMAKE_MATCH_3})
  set(label ${CMAKE_MATCH_4})
  string(REPLACE "<semicolon>" ";" value "${CMAKE_MATCH_5}")
  string(REPLACE "\\" "\\\\" value "${value}")
  string(REPLACE "\"" "\\\"" value "${value}")
  file(RELATIVE_PATH rel ${CASES} ${case_file})
  string(REGEX REPLACE "\\.json$" "" rel ${rel})
  set(out "${BINARY_DIR}/${peer}/${rel}")
  if(kind STREQUAL "refused")
    string(APPEND tests
           "add_test(\"${peer}.refused.${case_name}\" \"${ASPERITY}\" crosscheck \"${case_file}\""
           " --peer ${peer} --out \"${out}\" --quiet)\n"
           "set_tests_properties(\"${peer}.refused.${case_name}\" PROPERTIES LABELS \"${label}\""
           " PASS_REGULAR_EXPRESSION \"${value}\")\n")
  elseif(kind STREQUAL "polyhedra")
    if(NOT value MATCHES "^([^ ]+) \\(impulse ([^,]+), peak_force ([^,]+), contact_duration ([^)]+)\\)$")
      message(FATAL_ERROR "asperity crosscheck --list: a polyhedra line without its tolerances: ${line}")
    endif()
    string(APPEND tests
           "add_test(\"${peer}.${case_name}\" sh -c \"\\\"$0\\\" crosscheck \\\"$1\\\" --out \\\"$2\\\""
           " --max-rel-diff ${CMAKE_MATCH_1} --quiet && python3 \\\"$3\\\" \\\"$2/comparison.json\\\""
           " --impulse ${CMAKE_MATCH_2} --peak ${CMAKE_MATCH_3} --duration ${CMAKE_MATCH_4}\""
           " \"${ASPERITY}\" \"${case_file}\" \"${out}\" \"${CHECK_POLYHEDRA}\")\n"
           "set_tests_properties(\"${peer}.${case_name}\" PROPERTIES LABELS \"${label}\")\n")
  else()
    string(APPEND tests
           "add_test(\"${peer}.${case_name}\" \"${ASPERITY}\" crosscheck \"${case_file}\""
           " --peer ${peer} --out \"${out}\" --max-rel-diff ${value} --quiet)\n"
           "set_tests_properties(\"${peer}.${case_name}\" PROPERTIES LABELS \"${label}\")\n")
  endif()
endforeach()
file(WRITE ${OUT} "${tests}")
