# For the harness's self-test (tests/e2e/CMakeLists.txt): a line with a semicolon on stdout and on
# stderr.
execute_process(COMMAND "${CMAKE_COMMAND}" -E echo "stdout: first half; second half")
message("stderr: first half; second half")
