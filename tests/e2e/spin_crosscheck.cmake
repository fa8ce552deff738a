# Cross-checks semo's explicit search with SPIN on one model: fails unless both explore the same
# number of states and agree on every verdict.
#
#   cmake -DEXE=semo-verify -DINPUT=model.ir [-DSTRATEGY=strategy.xml] [-DROBOTS=dir]
#         [-DEXPECT=proven|violated] [-DDEPTH=k] [-DWORKDIR=dir] [-DSPIN=spin] [-DCC=gcc]
#         -P spin_crosscheck.cmake
#
# With DEPTH (for models too large to explore whole): the search on both sides is breadth-first and
# bounded to paths of DEPTH steps -- `check --max-depth DEPTH`, and pan built with -DBFS from
# `export --promela --spin-bfs`. `pan -mDEPTH` stores exactly the states within DEPTH steps, so the
# counts are compared as for a complete search; pan judges a state only when it expands it, so the
# verdicts come from a second run, `pan -m(DEPTH+1)`, which expands the states at depth DEPTH too.
#
# 1. `semo-verify check --json --engine explicit --no-symmetry --safety-only INPUT` (SPIN stores every state, so semo
#    must too; the LTL properties are not part of the cross-check, and leave the exit code 3): the state count, whether the search was complete, and the
#    verdict of each property (the invariants, and deadlock_freedom when the model has valid_end).
# 2. `semo-verify export --promela INPUT`, `spin -a`, `gcc -O2 -DNOREDUCE -DSAFETY`: no partial-order
#    reduction, so pan stores every reachable state, as semo does.
# 3. `./pan -c0 -n`: -c0 goes on after an error, so pan explores every reachable state and reports
#    every property that fails somewhere (each assertion names a hidden flag `prop_...`; the flag's
#    declaration in the Promela says which property it stands for).
# The check passes when the set of properties pan finds violated is exactly the set semo reports
# VIOLATED, pan reports no other error (no invalid end state, no depth limit), and -- when semo's
# search was complete, i.e. some property was proven -- pan's "states, stored" equals semo's
# "states". When every property is violated, semo stops early and the state counts are not compared.
# A modelling error (an update out of a variable's range) fails the check: semo stops there while
# pan would wrap the value, so there is nothing to compare (see checker/src/promela_export.cpp).
cmake_minimum_required(VERSION 3.19)  # string(JSON)

include("${CMAKE_CURRENT_LIST_DIR}/spin_common.cmake")
spin_script_arguments(spin_crosscheck)

set(semo_bound "")
set(export_bfs "")
set(pan_bfs "")
if(DEFINED DEPTH)
  set(semo_bound --max-depth ${DEPTH})
  set(export_bfs --spin-bfs)
  set(pan_bfs -DBFS)
endif()

# ---- semo
execute_process(COMMAND "${EXE}" check --json --engine explicit --no-symmetry --safety-only ${model_args} ${semo_bound}
  WORKING_DIRECTORY "${WORKDIR}" RESULT_VARIABLE code OUTPUT_VARIABLE json ERROR_VARIABLE err)
set(expected_codes "^[013]$")  # 3: a bound cut the search short, or LTL properties were not checked
if(NOT code MATCHES "${expected_codes}")
  message(FATAL_ERROR "semo-verify check exited with ${code} (${expected_codes} expected):\n${json}${err}")
endif()
string(JSON modelError ERROR_VARIABLE noModelError GET "${json}" modelError)
if(NOT noModelError)
  message(FATAL_ERROR "semo reports a modelling error (an update out of a variable's range); "
                      "SPIN would wrap the value instead, so this model cannot be cross-checked")
endif()
string(JSON semo_states GET "${json}" states)
string(JSON semo_complete GET "${json}" complete)
# Whether every state within reach (or within DEPTH steps) was explored: then the counts compare.
set(semo_counted ${semo_complete})
if(DEFINED DEPTH)
  string(JSON semo_bounded ERROR_VARIABLE not_bounded GET "${json}" boundedDepth)
  if(NOT not_bounded)
    set(semo_counted TRUE)
  endif()
endif()
string(JSON count LENGTH "${json}" properties)
set(semo_violated "")
set(semo_summary "")
if(count GREATER 0)
  math(EXPR last "${count} - 1")
  foreach(i RANGE ${last})
    string(JSON name GET "${json}" properties ${i} name)
    string(JSON verdict GET "${json}" properties ${i} verdict)
    string(APPEND semo_summary "  ${verdict} ${name}\n")
    if(verdict STREQUAL "VIOLATED")
      list(APPEND semo_violated "${name}")
    endif()
  endforeach()
endif()
list(SORT semo_violated)
message("semo: ${semo_states} states (complete: ${semo_complete}; counted: ${semo_counted}), exit ${code}\n${semo_summary}")
if(DEFINED EXPECT)
  if(EXPECT STREQUAL "proven" AND (NOT semo_complete OR NOT semo_violated STREQUAL ""))
    message(FATAL_ERROR "expected every safety property proven by a complete search, semo exited with ${code}")
  elseif(EXPECT STREQUAL "violated" AND NOT code EQUAL 1)
    message(FATAL_ERROR "expected a violated property (exit 1), semo exited with ${code}")
  endif()
endif()

# ---- SPIN
execute_process(COMMAND "${EXE}" export --promela ${export_bfs} ${model_args} -o "${WORKDIR}/model.pml"
  WORKING_DIRECTORY "${WORKDIR}" RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "semo-verify export --promela exited with ${code}:\n${out}${err}")
endif()
spin_build_pan(-DNOREDUCE -DSAFETY ${pan_bfs})

set(hash_bits 18)
while(hash_bits LESS 28)
  math(EXPR capacity "1 << ${hash_bits}")
  if(capacity GREATER semo_states)
    break()
  endif()
  math(EXPR hash_bits "${hash_bits} + 1")
endwhile()
if(DEFINED DEPTH)
  execute_process(COMMAND ./pan -m${DEPTH} -w${hash_bits} -c0 -n
    WORKING_DIRECTORY "${WORKDIR}" RESULT_VARIABLE code OUTPUT_VARIABLE count_out ERROR_VARIABLE err)
  if(NOT count_out MATCHES "([0-9]+) states, stored")
    message(FATAL_ERROR "cannot read pan's state count (exit ${code}):\n${count_out}${err}")
  endif()
  set(spin_states "${CMAKE_MATCH_1}")
  math(EXPR depth "${DEPTH} + 1")
  execute_process(COMMAND ./pan -m${depth} -w${hash_bits} -c0 -n
    WORKING_DIRECTORY "${WORKDIR}" RESULT_VARIABLE code OUTPUT_VARIABLE pan_out ERROR_VARIABLE err)
else()
  # The depth of pan's depth-first search is at most the number of states it stores (plus the few
  # steps of the timeout option); when semo stopped early that number is not known, so pan starts
  # with a guess and is run again with more room if it reports that the depth limit was too small.
  math(EXPR depth "${semo_states} * 2 + 1000")
  foreach(attempt RANGE 3)
    execute_process(COMMAND ./pan -m${depth} -w${hash_bits} -c0 -n
      WORKING_DIRECTORY "${WORKDIR}" RESULT_VARIABLE code OUTPUT_VARIABLE pan_out ERROR_VARIABLE err)
    if(NOT pan_out MATCHES "max search depth too small")
      break()
    endif()
    math(EXPR depth "${depth} * 10")
  endforeach()
endif()
if(NOT pan_out MATCHES "errors: ([0-9]+)")
  message(FATAL_ERROR "cannot read pan's output (exit ${code}):\n${pan_out}${err}")
endif()
set(spin_errors "${CMAKE_MATCH_1}")
if(NOT DEFINED DEPTH)
  if(NOT pan_out MATCHES "([0-9]+) states, stored")
    message(FATAL_ERROR "cannot read pan's state count:\n${pan_out}")
  endif()
  set(spin_states "${CMAKE_MATCH_1}")
endif()

# Which property each failed assertion stands for.
file(STRINGS "${WORKDIR}/model.pml" flag_lines REGEX "^(hidden )?byte [A-Za-z0-9_]+;.*/\\* property '")
set(flags "")
foreach(line IN LISTS flag_lines)
  string(REGEX MATCH "^(hidden )?byte ([A-Za-z0-9_]+);.*/\\* property '([^']+)'" _ "${line}")
  set(flag "${CMAKE_MATCH_2}")
  set(property_of_${flag} "${CMAKE_MATCH_3}")
  list(APPEND flags "${flag}")
endforeach()
string(REGEX MATCHALL "assertion violated [A-Za-z0-9_]+" failures "${pan_out}")
set(spin_violated "")
set(unexplained 0)
foreach(failure IN LISTS failures)
  string(REPLACE "assertion violated " "" flag "${failure}")
  if(DEFINED property_of_${flag})
    list(APPEND spin_violated "${property_of_${flag}}")
  else()
    math(EXPR unexplained "${unexplained} + 1")
  endif()
endforeach()
list(REMOVE_DUPLICATES spin_violated)
list(SORT spin_violated)
string(REGEX MATCHALL "pan:[0-9]+: [^\n]*" error_lines "${pan_out}")
list(LENGTH error_lines error_line_count)
list(LENGTH failures failure_count)
string(REGEX REPLACE "\n\n+" "\n" pan_summary "${pan_out}")
message("spin: ${spin_states} states stored, errors: ${spin_errors}; violated: ${spin_violated}\n${pan_summary}")

# ---- compare
set(problems "")
if(NOT spin_violated STREQUAL semo_violated)
  string(APPEND problems "violated properties differ: semo [${semo_violated}], SPIN [${spin_violated}]\n")
endif()
if(NOT failure_count EQUAL error_line_count OR unexplained GREATER 0)
  string(APPEND problems "pan reports errors that are not property assertions:\n")
  foreach(line IN LISTS error_lines)
    if(NOT line MATCHES "assertion violated prop_")
      string(APPEND problems "  ${line}\n")
    endif()
  endforeach()
endif()
if(NOT DEFINED DEPTH AND pan_out MATCHES "max search depth too small")
  string(APPEND problems "pan's depth limit (-m${depth}) was too small: its search is not complete\n")
endif()
if(semo_violated STREQUAL "" AND NOT spin_errors EQUAL 0)
  string(APPEND problems "semo finds no violation but pan reports ${spin_errors} errors\n")
endif()
if(semo_counted AND NOT spin_states EQUAL semo_states)
  string(APPEND problems "state counts differ: semo ${semo_states}, SPIN ${spin_states} stored\n")
endif()
if(problems)
  message(FATAL_ERROR "semo and SPIN disagree on ${INPUT}:\n${problems}(work files in ${WORKDIR})")
endif()
if(semo_counted AND DEFINED DEPTH)
  message("agree: ${semo_states} states within ${DEPTH} steps; violated: [${semo_violated}]")
elseif(semo_counted)
  message("agree: ${semo_states} states; violated: [${semo_violated}]")
else()
  message("agree on the verdicts (violated: [${semo_violated}]); semo stopped early, states not compared")
endif()
