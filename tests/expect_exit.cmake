# Runs a command and checks both its exit status and its output, which CTest's
# PASS_REGULAR_EXPRESSION alone does not (it ignores the exit status). Used by add_test as
#   ${CMAKE_COMMAND} -DRUN=<program|arg|arg...> -DEXPECT_EXIT=<code> -DEXPECT_OUTPUT=<regex>
#                    -P tests/expect_exit.cmake
# RUN separates the program and its arguments with '|'. The output checked is stdout and stderr
# together. Fails (a CMake error, so the test fails) naming what differed.
if(NOT DEFINED RUN OR NOT DEFINED EXPECT_EXIT OR NOT DEFINED EXPECT_OUTPUT)
  message(FATAL_ERROR "expect_exit.cmake needs -DRUN=..., -DEXPECT_EXIT=... and -DEXPECT_OUTPUT=...")
endif()
string(REPLACE "|" ";" command "${RUN}")
execute_process(COMMAND ${command} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT "${status}" STREQUAL "${EXPECT_EXIT}")
  message(FATAL_ERROR "exit status ${status}, expected ${EXPECT_EXIT}")
endif()
if(NOT "${out}${err}" MATCHES "${EXPECT_OUTPUT}")
  message(FATAL_ERROR "the output does not match '${EXPECT_OUTPUT}'")
endif()
