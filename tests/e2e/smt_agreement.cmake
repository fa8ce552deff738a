# Bounded model checking (Z3) against the explicit engine bounded to the same depth, on one model:
# fails unless both find the same properties violated within DEPTH steps, with counterexamples of
# the same length (both are shortest: breadth-first search, BMC by increasing depth).
# With -DDEPTH=full instead: the whole SMT engine (BMC, k-induction, IC3) against the complete
# explicit search; every safety property must get the same verdict from both, and none may stay
# unknown. Safety only, on both sides: the LTL verdicts of every engine are compared by
# engines_test.cpp.
#
#   cmake -DEXE=semo-verify -DINPUT=model.semo|model.ir [-DSTRATEGY=strategy.xml] -DDEPTH=k|full
#         -P smt_agreement.cmake
cmake_minimum_required(VERSION 3.19)  # string(JSON)

foreach(required EXE INPUT DEPTH)
  if(NOT DEFINED ${required})
    message(FATAL_ERROR "smt_agreement: -D${required}=... is required")
  endif()
endforeach()
set(model_args ${INPUT})
if(DEFINED STRATEGY)
  list(APPEND model_args --strategy ${STRATEGY})
endif()

# The violated properties of a JSON report, each as NAME=STEPS.
function(violations json out)
  set(found "")
  string(JSON count LENGTH "${json}" properties)
  math(EXPR last "${count} - 1")
  if(count GREATER 0)
    foreach(i RANGE ${last})
      string(JSON verdict GET "${json}" properties ${i} verdict)
      string(JSON type GET "${json}" properties ${i} type)
      if(verdict STREQUAL "VIOLATED" AND type STREQUAL "safety")
        string(JSON name GET "${json}" properties ${i} name)
        string(JSON steps LENGTH "${json}" properties ${i} counterexample steps)
        list(APPEND found "${name}=${steps}")
      endif()
    endforeach()
  endif()
  list(SORT found)
  set(${out} "${found}" PARENT_SCOPE)
endfunction()

# Every safety property as NAME=VERDICT.
function(verdicts json out)
  set(found "")
  string(JSON count LENGTH "${json}" properties)
  math(EXPR last "${count} - 1")
  foreach(i RANGE ${last})
    string(JSON type GET "${json}" properties ${i} type)
    if(type STREQUAL "safety")
      string(JSON name GET "${json}" properties ${i} name)
      string(JSON verdict GET "${json}" properties ${i} verdict)
      list(APPEND found "${name}=${verdict}")
    endif()
  endforeach()
  set(${out} "${found}" PARENT_SCOPE)
endfunction()

# Both runs end with a report (0 proven, 1 violated, 3 partial: with --safety-only, a model with LTL
# properties is partial), never with an error.
function(expect_report)
  foreach(code explicit_code smt_code)
    if(NOT ${code} MATCHES "^[013]$")
      message(FATAL_ERROR "smt_agreement: ${code} = ${${code}}")
    endif()
  endforeach()
endfunction()

# The safety properties both runs report: the same, and at least one (else nothing was compared).
function(same_properties)
  verdicts("${explicit_json}" explicit_verdicts)
  verdicts("${smt_json}" smt_verdicts)
  string(REGEX REPLACE "=[^;]*" "" explicit_names "${explicit_verdicts}")
  string(REGEX REPLACE "=[^;]*" "" smt_names "${smt_verdicts}")
  if(explicit_names STREQUAL "" OR NOT explicit_names STREQUAL smt_names)
    message(FATAL_ERROR "smt_agreement: the engines report different safety properties, or none: explicit [${explicit_names}], smt [${smt_names}]")
  endif()
endfunction()

if(DEPTH STREQUAL "full")
  execute_process(COMMAND ${EXE} check ${model_args} --json --engine explicit --no-symmetry --safety-only
                  OUTPUT_VARIABLE explicit_json RESULT_VARIABLE explicit_code)
  execute_process(COMMAND ${EXE} check ${model_args} --json --engine smt --safety-only
                  OUTPUT_VARIABLE smt_json RESULT_VARIABLE smt_code)
  expect_report()
  same_properties()
  verdicts("${explicit_json}" explicit_verdicts)
  verdicts("${smt_json}" smt_verdicts)
  if(NOT explicit_verdicts STREQUAL smt_verdicts OR smt_verdicts MATCHES "=unknown")
    message(FATAL_ERROR "smt_agreement: explicit [${explicit_verdicts}], smt [${smt_verdicts}]")
  endif()
  message(STATUS "smt_agreement: both decide [${smt_verdicts}]")
  return()
endif()

execute_process(COMMAND ${EXE} check ${model_args} --json --engine explicit --no-symmetry --safety-only --max-depth ${DEPTH}
                OUTPUT_VARIABLE explicit_json RESULT_VARIABLE explicit_code)
execute_process(COMMAND ${EXE} check ${model_args} --json --engine smt --max-depth ${DEPTH} --bmc-only --safety-only
                OUTPUT_VARIABLE smt_json RESULT_VARIABLE smt_code)
expect_report()
same_properties()
violations("${explicit_json}" explicit_found)
violations("${smt_json}" smt_found)
if(NOT explicit_found STREQUAL smt_found)
  message(FATAL_ERROR "smt_agreement: within ${DEPTH} steps the explicit engine finds [${explicit_found}], BMC [${smt_found}]")
endif()
message(STATUS "smt_agreement: within ${DEPTH} steps both find [${explicit_found}]")
