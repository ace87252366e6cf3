# problems_run.cmake - run a command and check its exit status and output.
#   cmake -DCMD=exe -DARGS=a@@b@@c -DEXPECT_RC=n [-DEXPECT_REGEX=re]
#         [-DREJECT_REGEX=re] [-DSTDERR_LINES=n] [-DEXPECT_ABSENT=path]
#         [-DREMOVE=path] -P problems_run.cmake
# ARGS separates arguments with "@@" (a ";" would not survive add_test).
# EXPECT_REGEX / REJECT_REGEX match stdout and stderr together.  A crash
# shows as a non-numeric exit status and fails.
string(REPLACE "@@" ";" args "${ARGS}")
if(DEFINED REMOVE)
  file(REMOVE "${REMOVE}")
endif()
execute_process(COMMAND ${CMD} ${args} RESULT_VARIABLE rc
                OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("command: ${CMD} ${args}\nexit status: ${rc}\n--- stdout\n${out}--- stderr\n${err}---")
if(NOT "${rc}" STREQUAL "${EXPECT_RC}")
  message(FATAL_ERROR "exit status ${rc}, expected ${EXPECT_RC}")
endif()
if(DEFINED EXPECT_REGEX AND NOT "${out}${err}" MATCHES "${EXPECT_REGEX}")
  message(FATAL_ERROR "output does not match '${EXPECT_REGEX}'")
endif()
if(DEFINED REJECT_REGEX AND "${out}${err}" MATCHES "${REJECT_REGEX}")
  message(FATAL_ERROR "output matches '${REJECT_REGEX}'")
endif()
if(DEFINED STDERR_LINES)
  string(REGEX MATCHALL "\n" nl "${err}")
  list(LENGTH nl n)
  if(NOT n EQUAL STDERR_LINES)
    message(FATAL_ERROR "${n} lines on stderr, expected ${STDERR_LINES}")
  endif()
endif()
if(DEFINED EXPECT_ABSENT AND EXISTS "${EXPECT_ABSENT}")
  message(FATAL_ERROR "${EXPECT_ABSENT} exists but should not")
endif()
