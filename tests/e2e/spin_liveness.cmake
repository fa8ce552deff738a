# Cross-checks semo's LTL verdicts with SPIN on one small model: fails unless, for every property,
# pan's search for an acceptance cycle of the claim `fairness -> property` agrees with semo.
#
#   cmake -DEXE=semo-verify -DINPUT=model [-DSTRATEGY=strategy.xml] [-DWORKDIR=dir] [-DSPIN=spin]
#         [-DCC=gcc] -P spin_liveness.cmake
#
# 1. `semo-verify check --json --engine explicit --no-slicing --no-symmetry INPUT`: the verdict of each LTL property
#    on the whole product (and, for the record, `check --json` with every reduction, which must
#    agree with it).
# 2. `semo-verify export --promela --spin-ltl INPUT`: the model with the rule of the last step kept in
#    `semo_last` and one `ltl` claim per property whose premise is semo's fairness (a fair group
#    enabled for ever is taken again and again, ...) and, on a settling world, that every sensed
#    condition is from some point on decided one way (specs/ir.md), kept as flags by the model
#    (checker/promela_export.hpp).
# 3. `spin -a`, `gcc -O2 pan.c` (SPIN's partial-order reduction on, as for any LTL claim), and per
#    property `./pan -a -N claim`: an acceptance cycle is a violation, none a proof.
cmake_minimum_required(VERSION 3.19)  # string(JSON)

include("${CMAKE_CURRENT_LIST_DIR}/spin_common.cmake")
spin_script_arguments(spin_liveness)

# -DTRANSLATE_ONLY=ON: only that SPIN translates every claim (for the examples, whose searches, and
# even pan's compilation with their claims, take minutes).
if(TRANSLATE_ONLY)
  execute_process(COMMAND "${EXE}" export --promela --spin-ltl ${model_args} -o "${WORKDIR}/model.pml"
    WORKING_DIRECTORY "${WORKDIR}" RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "semo-verify export --promela --spin-ltl exited with ${code}:\n${out}${err}")
  endif()
  spin_translate()
  file(STRINGS "${WORKDIR}/model.pml" claims REGEX "^ltl ")
  list(LENGTH claims count)
  message("spin translated ${count} claims")
  return()
endif()

# The LTL verdicts of a `check --json` output, as name=verdict items.
function(ltl_verdicts json out)
  string(JSON count LENGTH "${json}" properties)
  set(items "")
  math(EXPR last "${count} - 1")
  foreach(i RANGE ${last})
    string(JSON type GET "${json}" properties ${i} type)
    if(NOT type STREQUAL "liveness")
      continue()
    endif()
    string(JSON name GET "${json}" properties ${i} name)
    string(JSON verdict GET "${json}" properties ${i} verdict)
    list(APPEND items "${name}=${verdict}")
  endforeach()
  set(${out} "${items}" PARENT_SCOPE)
endfunction()

# ---- semo
execute_process(COMMAND "${EXE}" check --json --engine explicit --no-slicing --no-symmetry ${model_args}
  WORKING_DIRECTORY "${WORKDIR}" RESULT_VARIABLE code OUTPUT_VARIABLE json ERROR_VARIABLE err)
if(NOT code MATCHES "^[01]$")
  message(FATAL_ERROR "semo-verify check exited with ${code} (0 or 1 expected: every property decided):\n${json}${err}")
endif()
ltl_verdicts("${json}" semo)
execute_process(COMMAND "${EXE}" check --json ${model_args}
  WORKING_DIRECTORY "${WORKDIR}" RESULT_VARIABLE code OUTPUT_VARIABLE json ERROR_VARIABLE err)
ltl_verdicts("${json}" reduced)
if(NOT semo STREQUAL reduced)
  message(FATAL_ERROR "semo's reductions change a verdict: whole product ${semo}, with reductions ${reduced}")
endif()
list(LENGTH semo properties)
if(properties EQUAL 0)
  message(FATAL_ERROR "the model has no LTL property to cross-check")
endif()
message("semo: ${semo}")

# ---- SPIN
execute_process(COMMAND "${EXE}" export --promela --spin-ltl ${model_args} -o "${WORKDIR}/model.pml"
  WORKING_DIRECTORY "${WORKDIR}" RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "semo-verify export --promela --spin-ltl exited with ${code}:\n${out}${err}")
endif()
spin_build_pan()
file(STRINGS "${WORKDIR}/model.pml" claim_lines REGEX "^ltl [A-Za-z0-9_]+ \\{  /\\* ")
set(problems "")
foreach(line IN LISTS claim_lines)
  string(REGEX MATCH "^ltl ([A-Za-z0-9_]+) \\{  /\\* (.*) \\*/$" _ "${line}")
  set(claim "${CMAKE_MATCH_1}")
  set(name "${CMAKE_MATCH_2}")
  execute_process(COMMAND ./pan -a -N ${claim} -m1000000
    WORKING_DIRECTORY "${WORKDIR}" RESULT_VARIABLE code OUTPUT_VARIABLE pan_out ERROR_VARIABLE err)
  if(NOT pan_out MATCHES "errors: ([0-9]+)")
    message(FATAL_ERROR "cannot read pan's output for ${claim} (exit ${code}):\n${pan_out}${err}")
  endif()
  set(errors "${CMAKE_MATCH_1}")
  if(pan_out MATCHES "max search depth too small")
    message(FATAL_ERROR "pan's depth limit cut the search for ${claim} short")
  endif()
  if(errors EQUAL 0)
    set(spin_verdict proven)
  elseif(pan_out MATCHES "acceptance cycle")
    set(spin_verdict VIOLATED)
  else()
    message(FATAL_ERROR "pan reports an error that is not an acceptance cycle for ${claim}:\n${pan_out}")
  endif()
  string(REGEX MATCH "([0-9]+) states, stored" _ "${pan_out}")
  message("spin: ${name}=${spin_verdict} (${CMAKE_MATCH_1} states stored)")
  if(NOT "${name}=${spin_verdict}" IN_LIST semo)
    string(APPEND problems "  ${name}: SPIN says ${spin_verdict}, semo says otherwise (${semo})\n")
  endif()
endforeach()
list(LENGTH claim_lines claims)
if(NOT claims EQUAL properties)
  string(APPEND problems "  ${claims} claims for ${properties} properties\n")
endif()
if(NOT problems STREQUAL "")
  message(FATAL_ERROR "semo and SPIN disagree:\n${problems}")
endif()
