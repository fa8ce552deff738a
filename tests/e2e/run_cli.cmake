# Runs a program (semo-verify) once in an empty working folder and checks its exit code, its output,
# and that it wrote no file. Variables: EXE, ARGS ("|"-separated), EXPECT_EXIT, WORKDIR, and the
# files holding the regular expressions: STDOUT_FILE, STDERR_FILE (must match), NOT_STDOUT_FILE,
# NOT_STDERR_FILE (must not match). A pattern is read from its file whole, `;` and all
# (tests/e2e/CMakeLists.txt, semo_cli_test).
string(REPLACE "|" ";" args "${ARGS}")
file(REMOVE_RECURSE "${WORKDIR}")
file(MAKE_DIRECTORY "${WORKDIR}")
execute_process(COMMAND "${EXE}" ${args}
  WORKING_DIRECTORY "${WORKDIR}"
  RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("exit ${code}\n--- stdout\n${out}--- stderr\n${err}---")
if(NOT code STREQUAL "${EXPECT_EXIT}")
  message(FATAL_ERROR "expected exit code ${EXPECT_EXIT}, got ${code}")
endif()
foreach(kind STDOUT STDERR NOT_STDOUT NOT_STDERR)
  if(NOT DEFINED ${kind}_FILE)
    continue()
  endif()
  file(READ "${${kind}_FILE}" pattern)
  if(kind MATCHES "OUT$")
    set(stream "${out}")
    set(stream_name stdout)
  else()
    set(stream "${err}")
    set(stream_name stderr)
  endif()
  if(kind MATCHES "^NOT_")
    if(stream MATCHES "${pattern}")
      message(FATAL_ERROR "${stream_name} must not match: ${pattern}")
    endif()
  elseif(NOT stream MATCHES "${pattern}")
    message(FATAL_ERROR "${stream_name} does not match: ${pattern}")
  endif()
endforeach()
file(GLOB written "${WORKDIR}/*")
if(written)
  message(FATAL_ERROR "${EXE} wrote files it should not have: ${written}")
endif()
