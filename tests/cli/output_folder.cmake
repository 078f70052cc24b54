# Output folders are all or nothing: a rerun replaces what an earlier run wrote, a failed
# write leaves the earlier outputs as they were and no staging folder, and a folder of other
# files is refused before any work.
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
set(world "${SOURCE_DIR}/worlds/lab.yaml")

execute_process(COMMAND "${COOPMAP}" run "${world}" --duration 2 --quiet --out "${WORK_DIR}/out"
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT EXISTS "${WORK_DIR}/out/map_eric.pgm"
   OR NOT EXISTS "${WORK_DIR}/out/.coopmap-output")
  message(FATAL_ERROR "a two-robot run did not write its outputs (rc ${rc}):\n${err}")
endif()
file(READ "${WORK_DIR}/out/metrics.json" two_robots)

# One robot into the two-robot folder: nothing of the first run stays.
execute_process(COMMAND "${COOPMAP}" run "${world}" --duration 2 --quiet --robots 1
                        --out "${WORK_DIR}/out"
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the one-robot rerun failed (rc ${rc}):\n${err}")
endif()
foreach(stale map_eric.pgm traverse_eric.traverse trajectory_eric_odometry.tum)
  if(EXISTS "${WORK_DIR}/out/${stale}")
    message(FATAL_ERROR "the rerun kept the earlier run's ${stale}")
  endif()
endforeach()
file(READ "${WORK_DIR}/out/metrics.json" one_robot)

# A write that fails part-way (files limited to 50 KiB: the traverse logs are larger): an
# error, the previous outputs as they were, nothing beside them.
execute_process(COMMAND bash -c "trap '' XFSZ; ulimit -f 50; exec \"$0\" run \"$1\" --duration 20 --quiet --out \"$2\""
                        "${COOPMAP}" "${world}" "${WORK_DIR}/out"
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "File too large")
  message(FATAL_ERROR "a run whose writes failed did not say so (rc ${rc}):\n${err}")
endif()
file(READ "${WORK_DIR}/out/metrics.json" after_failure)
if(NOT after_failure STREQUAL one_robot)
  message(FATAL_ERROR "a failed run changed the earlier outputs")
endif()
file(GLOB beside RELATIVE "${WORK_DIR}" "${WORK_DIR}/*")
if(NOT beside STREQUAL "out")
  message(FATAL_ERROR "a failed run left files beside its folder: ${beside}")
endif()

# A folder of other files is refused before the run, untouched.
file(WRITE "${WORK_DIR}/mine/notes.txt" "mine")
execute_process(COMMAND "${COOPMAP}" run "${world}" --duration 2 --quiet --out "${WORK_DIR}/mine"
                        --record "${WORK_DIR}/rec"
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 2 OR NOT err MATCHES "--out: expected an empty folder or one coopmap wrote")
  message(FATAL_ERROR "a folder of other files was not refused (rc ${rc}):\n${err}")
endif()
file(GLOB mine RELATIVE "${WORK_DIR}/mine" "${WORK_DIR}/mine/*")
if(NOT mine STREQUAL "notes.txt" OR EXISTS "${WORK_DIR}/rec")
  message(FATAL_ERROR "a refused run wrote something: ${mine}")
endif()
execute_process(COMMAND "${COOPMAP}" run "${world}" --duration 2 --quiet --out "${WORK_DIR}/o2"
                        --record "${WORK_DIR}/mine"
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 2 OR NOT err MATCHES "--record: expected an empty folder or one coopmap wrote"
   OR EXISTS "${WORK_DIR}/o2")
  message(FATAL_ERROR "a --record folder of other files was not refused (rc ${rc}):\n${err}")
endif()
message(STATUS "output folders are all or nothing")
