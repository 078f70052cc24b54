# `coopmap run --shared-map DIR`: the shared map service keeps the map in DIR; a second run on
# the same folder goes on from it (its robots' posts are new posts, not duplicates); a
# corrupt or foreign folder is refused with exit 2 naming it.
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
set(world "${SOURCE_DIR}/worlds/lab.yaml")
set(map "${WORK_DIR}/map")

foreach(run 1 2)
  execute_process(COMMAND "${COOPMAP}" run "${world}" --seed ${run} --quiet --shared-map "${map}"
                          --out "${WORK_DIR}/out${run}"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0 OR NOT EXISTS "${map}/shared_map.bin")
    message(FATAL_ERROR "run ${run} on --shared-map did not keep the map (rc ${rc}):\n${out}${err}")
  endif()
  if(NOT out MATCHES "jose sortie 1 at [0-9]+ s: [0-9]+ scans, fixed, posted"
     OR NOT out MATCHES "eric sortie 1 at [0-9]+ s: [0-9]+ scans, fixed, posted")
    message(FATAL_ERROR "run ${run}: a robot's post did not go in:\n${out}")
  endif()
  file(SIZE "${map}/shared_map.bin" size${run})
endforeach()

# The kept map is read back by a third run: a corrupt one is refused, naming the file.
file(READ "${map}/shared_map.bin" bytes HEX LIMIT 64)
file(WRITE "${map}/shared_map.bin" "${bytes}")
execute_process(COMMAND "${COOPMAP}" run "${world}" --quiet --shared-map "${map}" --duration 1
                        --out "${WORK_DIR}/out3"
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 2 OR NOT err MATCHES "--shared-map: .*shared_map.bin: "
   OR EXISTS "${WORK_DIR}/out3")
  message(FATAL_ERROR "a corrupt shared map was not refused clearly (rc ${rc}):\n${err}")
endif()
file(WRITE "${WORK_DIR}/a_file" "x")
execute_process(COMMAND "${COOPMAP}" run "${world}" --quiet --shared-map "${WORK_DIR}/a_file"
                        --out "${WORK_DIR}/out4"
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 2 OR NOT err MATCHES "--shared-map")
  message(FATAL_ERROR "--shared-map naming a file was not refused (rc ${rc}):\n${err}")
endif()
message(STATUS "the shared map is kept across runs")
