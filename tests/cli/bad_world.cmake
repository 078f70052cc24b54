# The command line on bad input: a clear message naming file, line and field, a non-zero
# exit code, and nothing written.
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
file(READ "${SOURCE_DIR}/worlds/lab.yaml" lab)
string(REPLACE "thickness: 0.1, height: 2.5, texture: brick}      # south"
               "thickness: -3, height: 2.5, texture: brick}      # south" broken "${lab}")
if(broken STREQUAL lab)
  message(FATAL_ERROR "test setup: the line to break was not found in worlds/lab.yaml")
endif()
# Keep relative model paths valid: write the broken world next to the real one's folder.
set(world "${SOURCE_DIR}/worlds/.broken_for_test.yaml")
file(WRITE "${world}" "${broken}")
execute_process(COMMAND "${COOPMAP}" run "${world}" --out "${WORK_DIR}/out" --quiet
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
file(REMOVE "${world}")
if(rc EQUAL 0)
  message(FATAL_ERROR "coopmap accepted a broken world:\n${out}${err}")
endif()
if(NOT err MATCHES "\\.broken_for_test\\.yaml:[0-9]+:[0-9]+: walls\\[0\\]\\.thickness: expected a positive thickness")
  message(FATAL_ERROR "unclear error message:\n${err}")
endif()
if(EXISTS "${WORK_DIR}/out")
  message(FATAL_ERROR "coopmap wrote outputs for a broken world")
endif()

execute_process(COMMAND "${COOPMAP}" run "${SOURCE_DIR}/worlds/lab.yaml" --out "${WORK_DIR}/out"
                        --duration -5
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "duration")
  message(FATAL_ERROR "a negative --duration was not rejected clearly (rc ${rc}):\n${err}")
endif()

execute_process(COMMAND "${COOPMAP}" run --help RESULT_VARIABLE rc OUTPUT_VARIABLE out)
if(NOT rc EQUAL 0 OR NOT out MATCHES "--seed" OR NOT out MATCHES "metrics.json")
  message(FATAL_ERROR "coopmap run --help does not explain the options:\n${out}")
endif()
message(STATUS "bad input is reported clearly")

# Seeds are unsigned 64-bit numbers as typed: no wrapping, no capping; a bad option exits 2
# as every other bad input does.
foreach(seed "-1" "99999999999999999999999" "18446744073709551616" "1.5" "")
  execute_process(COMMAND "${COOPMAP}" run "${SOURCE_DIR}/worlds/lab.yaml" --out "${WORK_DIR}/seed"
                          --seed "${seed}" --duration 0.5 --quiet
                  RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(NOT rc EQUAL 2 OR NOT err MATCHES "--seed: expected an integer from 0 to 18446744073709551615")
    message(FATAL_ERROR "--seed '${seed}' was not refused clearly (rc ${rc}):\n${err}")
  endif()
  if(EXISTS "${WORK_DIR}/seed")
    message(FATAL_ERROR "coopmap wrote outputs for --seed '${seed}'")
  endif()
endforeach()
execute_process(COMMAND "${COOPMAP}" run "${SOURCE_DIR}/worlds/lab.yaml" --out "${WORK_DIR}/seed"
                        --seed 18446744073709551615 --duration 0.5 --quiet
                RESULT_VARIABLE rc ERROR_VARIABLE err)
file(READ "${WORK_DIR}/seed/metrics.json" metrics)
if(NOT rc EQUAL 0 OR NOT metrics MATCHES "\"seed\": 18446744073709551615")
  message(FATAL_ERROR "the largest seed did not run as itself (rc ${rc}):\n${err}")
endif()
execute_process(COMMAND "${COOPMAP}" run "${SOURCE_DIR}/worlds/lab.yaml" --out "${WORK_DIR}/x"
                        --no-such-option
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 2)
  message(FATAL_ERROR "an unknown option exited ${rc}, expected 2:\n${err}")
endif()

# --out is checked before any work: empty, a file, or under a file is refused with exit 2.
file(WRITE "${WORK_DIR}/a_file" "not a folder")
foreach(out "" "${WORK_DIR}/a_file" "${WORK_DIR}/a_file/sub")
  execute_process(COMMAND "${COOPMAP}" run "${SOURCE_DIR}/worlds/lab.yaml" --out "${out}"
                          --record "${WORK_DIR}/rec_for_bad_out" --quiet
                  RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(NOT rc EQUAL 2 OR NOT err MATCHES "--out: expected a folder to write to")
    message(FATAL_ERROR "--out '${out}' was not refused before the run (rc ${rc}):\n${err}")
  endif()
  if(EXISTS "${WORK_DIR}/rec_for_bad_out")
    message(FATAL_ERROR "a run with a bad --out wrote its --record folder")
  endif()
endforeach()

execute_process(COMMAND "${COOPMAP}" --version RESULT_VARIABLE rc OUTPUT_VARIABLE out)
if(NOT rc EQUAL 0 OR NOT out MATCHES "^[0-9]+\\.[0-9]+\\.[0-9]+")
  message(FATAL_ERROR "coopmap --version printed no version (rc ${rc}): ${out}")
endif()
