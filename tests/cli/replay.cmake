# `coopmap run --record` and `coopmap replay`: the same agents run on a recording, observe-only,
# reproduce the live run's maps and traverse logs byte for byte (two exploring robots, each
# placed by its look at the home base, sorties ended at home: corrected, posted, the shared
# map imported); a broken recording gets a message naming
# the file and frame, a non-zero exit code, and nothing written.
include("${CMAKE_CURRENT_LIST_DIR}/helpers.cmake")
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
execute_process(COMMAND "${COOPMAP}" run "${SOURCE_DIR}/worlds/lab.yaml" --out "${WORK_DIR}/live"
                        --record "${WORK_DIR}/rec" --explore --duration 150 --max-sorties 3
                        --first-sortie-budget-m 4 --sortie-budget-m 4 --quiet
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "coopmap run --record failed (rc ${rc}):\n${out}${err}")
endif()
if(NOT out MATCHES "jose sortie 1 at [0-9]+ s: [0-9]+ scans, fixed, posted")
  message(FATAL_ERROR "the recorded run ended no sortie at home:\n${out}")
endif()
foreach(f README.md dataset.yaml jose/robot.yaml jose/frames.csv jose/odometry.csv
          jose/commands.csv jose/status.csv jose/agent.yaml jose/groundtruth.csv
          jose/images/000003_vertical.png eric/agent.yaml)
  if(NOT EXISTS "${WORK_DIR}/rec/${f}")
    message(FATAL_ERROR "coopmap run --record did not write ${f}")
  endif()
endforeach()

execute_process(COMMAND "${COOPMAP}" replay "${WORK_DIR}/rec" --out "${WORK_DIR}/replay"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "jose: [0-9]+ frames")
  message(FATAL_ERROR "coopmap replay failed on a good recording (rc ${rc}):\n${out}${err}")
endif()
foreach(f map_jose.pgm map_jose.yaml map_jose.png traverse_jose.traverse
          trajectory_jose_odometry.tum map_eric.pgm traverse_eric.traverse
          trajectory_eric_groundtruth.tum)
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files "${WORK_DIR}/live/${f}"
                          "${WORK_DIR}/replay/${f}" RESULT_VARIABLE same)
  if(NOT same EQUAL 0)
    message(FATAL_ERROR "the replayed ${f} differs from the live run's")
  endif()
endforeach()

# A corrupt image.
file(WRITE "${WORK_DIR}/rec/jose/images/000003_horizontal.png" "not a png")
expect_exit2("a corrupt image" "rec/jose/images/000003_horizontal\\.png: frame 3: expected a PNG image"
             replay "${WORK_DIR}/rec" --out "${WORK_DIR}/bad")
if(EXISTS "${WORK_DIR}/bad")
  message(FATAL_ERROR "coopmap replay wrote outputs for a corrupt recording")
endif()

# An unknown version.
file(READ "${WORK_DIR}/rec/dataset.yaml" dataset)
string(REPLACE "version: 2" "version: 9" dataset "${dataset}")
file(WRITE "${WORK_DIR}/rec/dataset.yaml" "${dataset}")
execute_process(COMMAND "${COOPMAP}" replay "${WORK_DIR}/rec" --out "${WORK_DIR}/bad"
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "rec/dataset\\.yaml:3:10: version: version 9 is not supported")
  message(FATAL_ERROR "an unknown version was not rejected clearly (rc ${rc}):\n${err}")
endif()

# No dataset.yaml: not a complete recording.
file(REMOVE "${WORK_DIR}/rec/dataset.yaml")
execute_process(COMMAND "${COOPMAP}" replay "${WORK_DIR}/rec" --out "${WORK_DIR}/bad"
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "rec/dataset\\.yaml: missing file: not a complete coopmap")
  message(FATAL_ERROR "an incomplete recording was not rejected clearly (rc ${rc}):\n${err}")
endif()
if(EXISTS "${WORK_DIR}/bad")
  message(FATAL_ERROR "coopmap replay wrote outputs for a broken recording")
endif()
message(STATUS "coopmap replay reproduces a recording and reports a broken one clearly")
