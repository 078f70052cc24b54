# `coopmap world generate`: bad options exit with code 2, a message naming the option, and
# nothing written; a generated world, written far from the source tree, runs.
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}/deep/folder")
set(world "${WORK_DIR}/deep/folder/generated.yaml")

function(expect_rejected pattern)
  execute_process(COMMAND "${COOPMAP}" world generate ${ARGN}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 2 OR NOT err MATCHES "${pattern}")
    message(FATAL_ERROR "'world generate ${ARGN}' was not rejected clearly (rc ${rc}):\n${out}${err}")
  endif()
  file(GLOB written "${WORK_DIR}/deep/folder/*")
  if(written)
    message(FATAL_ERROR "'world generate ${ARGN}' wrote ${written}")
  endif()
endfunction()

expect_rejected("--family: expected one of corridor, lt, loop, open, got 'maze'"
                --seed 1 --family maze --out "${world}")
expect_rejected("--area: expected a floor area in \\[100, 600\\] m\\^2, got 700"
                --seed 1 --area 700 --out "${world}")
expect_rejected("--area: expected a floor area in m\\^2, got 'big'"
                --seed 1 --area big --out "${world}")
expect_rejected("--out: expected the path of the world file to write" --seed 1)
expect_rejected("--seed: expected a non-negative integer, got '-3'" --seed -3 --out "${world}")
expect_rejected("--out: expected a writable file path: cannot write '${WORK_DIR}/missing/w.yaml'"
                --seed 1 --out "${WORK_DIR}/missing/w.yaml")

# A world that runs: a few simulated seconds, from the output folder's relative model path.
execute_process(COMMAND "${COOPMAP}" world generate --seed 5 --family corridor --area 150
                        --out "${world}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT EXISTS "${world}" OR NOT out MATCHES "corridor building")
  message(FATAL_ERROR "world generate failed (rc ${rc}):\n${out}${err}")
endif()
execute_process(COMMAND "${COOPMAP}" run "${world}" --duration 5 --quiet --out "${WORK_DIR}/run"
                WORKING_DIRECTORY "${WORK_DIR}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT EXISTS "${WORK_DIR}/run/metrics.json")
  message(FATAL_ERROR "the generated world did not run (rc ${rc}):\n${out}${err}")
endif()
message(STATUS "world generate rejects bad options and writes a world that runs")
