# Lists the tests of a GoogleTest binary and writes a CTest file that runs them in chunks: the
# tests of one suite, in their order, in one process while their estimated cost stays within
# BUDGET_S. A device test pays a process's start, the Vulkan instance with its validation layer
# and the renderer's pipelines (about 2 s on lavapipe) before it draws anything; run one to a
# process, that was most of the suite's time. Run after the binary is built (cmake -P):
#   EXE        the test binary
#   OUT        the CTest file to write (included by the test directory's CTestTestfile)
#   COSTS      per-test costs, "Suite.Test runs seconds" lines (tests/ctest_costs.txt)
#   COSTS_OUT  the chunks' costs in the same format, to seed ctest's order on a fresh build
#   SLOW       a regex: matching tests run one to a process, labelled slow
#   BUDGET_S   a chunk's estimated cost, seconds
#   TIMEOUT_S  a chunk's (and a slow test's) timeout
#   ENV        the tests' ENVIRONMENT property
cmake_minimum_required(VERSION 3.22)

execute_process(COMMAND "${EXE}" --gtest_list_tests OUTPUT_VARIABLE listing
                RESULT_VARIABLE status ERROR_VARIABLE error)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "gtest_chunks: ${EXE} --gtest_list_tests failed (${status}): ${error}")
endif()

# Per-test costs measured one test to a process; tests not listed are assumed to cost
# DEFAULT_COST_S (most are unit tests of well under a second).
set(DEFAULT_COST_S 1)
file(STRINGS "${COSTS}" cost_lines REGEX "^[^ ]+ [0-9]+ [0-9]+(\\.[0-9]*)?$")
foreach(line IN LISTS cost_lines)
  string(REGEX MATCH "^([^ ]+) [0-9]+ ([0-9]+)" _ "${line}")  # whole seconds
  string(MAKE_C_IDENTIFIER "${CMAKE_MATCH_1}" key)
  set("cost_${key}" "${CMAKE_MATCH_2}")
endforeach()

# Comments after the names ("# GetParam() = ...") can hold anything, semicolons included.
string(REPLACE ";" "," listing "${listing}")
string(REPLACE "\n" ";" lines "${listing}")

set(script "# Written by cmake/gtest_chunks.cmake from ${EXE} --gtest_list_tests\n")
set(costs_out "")
set(suite "")
set(chunk "")        # gtest filter of the chunk being filled
set(chunk_cost 0)
set(chunk_index 0)

# A ctest test NAME that runs the tests FILTER selects, with further PROPERTIES.
macro(emit_test name filter properties)
  string(APPEND script "add_test([==[${name}]==] [==[${EXE}]==] [==[--gtest_filter=${filter}]==])\n"
         "set_tests_properties([==[${name}]==] PROPERTIES TIMEOUT ${TIMEOUT_S} ${properties} "
         "ENVIRONMENT [==[${ENV}]==])\n")
endmacro()

macro(add_chunk)
  if(NOT chunk STREQUAL "")
    math(EXPR chunk_index "${chunk_index} + 1")
    set(name "${suite}part${chunk_index}")
    emit_test("${name}" "${chunk}" "")
    string(APPEND costs_out "${name} 1 ${chunk_cost}\n")
  endif()
  set(chunk "")
  set(chunk_cost 0)
endmacro()

foreach(line IN LISTS lines)
  string(REGEX REPLACE " *#.*$" "" line "${line}")
  if(line MATCHES "^([^ ].*\\.)$")  # a suite: "Suite." or "Prefix/Suite."
    add_chunk()
    set(suite "${CMAKE_MATCH_1}")
    set(chunk_index 0)
  elseif(line MATCHES "^  ([^ ]+)$")
    set(test "${suite}${CMAKE_MATCH_1}")
    if(test MATCHES "DISABLED_")  # gtest would not run it in a chunk either
      continue()
    endif()
    if(test MATCHES "${SLOW}")
      emit_test("${test}" "${test}" "LABELS slow")
      continue()
    endif()
    string(MAKE_C_IDENTIFIER "${test}" key)
    set(cost "${DEFAULT_COST_S}")
    if(DEFINED "cost_${key}")
      set(cost "${cost_${key}}")
    endif()
    math(EXPR sum "${chunk_cost} + ${cost}" OUTPUT_FORMAT DECIMAL)
    if(NOT chunk STREQUAL "" AND sum GREATER BUDGET_S)
      add_chunk()
      set(sum "${cost}")
    endif()
    if(chunk STREQUAL "")
      set(chunk "${test}")
    else()
      string(APPEND chunk ":${test}")
    endif()
    set(chunk_cost "${sum}")
  endif()
endforeach()
add_chunk()

file(WRITE "${OUT}" "${script}")
file(WRITE "${COSTS_OUT}" "${costs_out}---\n")
