# What the SPIN scripts (spin_crosscheck.cmake, spin_liveness.cmake) share: their arguments and
# work folder, and building pan from an exported model. Included, not run.

# spin_script_arguments(SCRIPT): checks -DEXE and -DINPUT, defaults SPIN, CC and WORKDIR (emptied),
# and sets model_args to the model as semo-verify takes it (with --strategy, --robots if given).
macro(spin_script_arguments script)
  foreach(required EXE INPUT)
    if(NOT DEFINED ${required})
      message(FATAL_ERROR "${script}: -D${required}=... is required")
    endif()
  endforeach()
  if(NOT DEFINED SPIN)
    set(SPIN spin)
  endif()
  if(NOT DEFINED CC)
    set(CC gcc)
  endif()
  if(NOT DEFINED WORKDIR)
    get_filename_component(stem "${INPUT}" NAME_WE)
    set(WORKDIR "${CMAKE_CURRENT_BINARY_DIR}/${script}_${stem}")
  endif()
  file(REMOVE_RECURSE "${WORKDIR}")
  file(MAKE_DIRECTORY "${WORKDIR}")
  set(model_args "${INPUT}")
  if(DEFINED STRATEGY)
    list(APPEND model_args --strategy "${STRATEGY}")
  endif()
  if(DEFINED ROBOTS)
    list(APPEND model_args --robots "${ROBOTS}")
  endif()
endmacro()

# spin_translate(): `spin -a model.pml` in WORKDIR (the claims translated, pan.c written).
function(spin_translate)
  execute_process(COMMAND "${SPIN}" -a model.pml
    WORKING_DIRECTORY "${WORKDIR}" RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL 0 OR out MATCHES "error" OR err MATCHES "error")
    message(FATAL_ERROR "spin -a failed (${code}):\n${out}${err}")
  endif()
endfunction()

# spin_build_pan(FLAGS...): spin_translate(), then `CC -O2 FLAGS -o pan pan.c` in WORKDIR.
function(spin_build_pan)
  spin_translate()
  execute_process(COMMAND "${CC}" -O2 -w ${ARGN} -o pan pan.c
    WORKING_DIRECTORY "${WORKDIR}" RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "compiling pan.c failed (${code}):\n${out}${err}")
  endif()
endfunction()
