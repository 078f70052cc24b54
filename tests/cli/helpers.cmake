# What the CLI tests share (include()d by them; COOPMAP, SOURCE_DIR and WORK_DIR are set).

# coopmap ARGN exits 2 (bad input) and its stderr matches `pattern`.
function(expect_exit2 what pattern)
  execute_process(COMMAND "${COOPMAP}" ${ARGN} RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(NOT rc EQUAL 2 OR NOT err MATCHES "${pattern}")
    message(FATAL_ERROR "${what}: expected exit 2 and an error matching\n  ${pattern}\n"
                        "got (rc ${rc}):\n${err}")
  endif()
endfunction()

# A one-second run of the lab's two robots, recorded into `record`, its outputs in `out`.
function(record_lab record out)
  execute_process(COMMAND "${COOPMAP}" run "${SOURCE_DIR}/worlds/lab.yaml" --duration 1 --quiet
                          --record "${record}" --out "${out}"
                  RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "test setup: the recorded run failed:\n${err}")
  endif()
endfunction()
