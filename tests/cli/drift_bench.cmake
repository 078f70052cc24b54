# `coopmap bench drift` writes the files the issue names with the columns it names, and
# `coopmap traverse` reports a corrupt traverse log with the file, record and offset.
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
execute_process(COMMAND "${COOPMAP}" bench drift --world "${SOURCE_DIR}/worlds/lab.yaml"
                        --seeds 1 --out "${WORK_DIR}/drift" --models none heading-drift --quiet
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "coopmap bench drift failed (${rc}):\n${out}${err}")
endif()
file(STRINGS "${WORK_DIR}/drift/drift.csv" rows)
list(GET rows 0 header)
foreach(column seed model path_length_m odometry_error_m odometry_error_deg ate_rmse_m
               wall_recall false_occupied_rate correct_ms)
  if(NOT header MATCHES "(^|,)${column}(,|$)")
    message(FATAL_ERROR "drift.csv lacks the column ${column}: ${header}")
  endif()
endforeach()
list(LENGTH rows n)
if(NOT n EQUAL 4)  # header, none, heading-drift, ground-truth
  message(FATAL_ERROR "drift.csv: expected 3 rows, got:\n${rows}")
endif()
foreach(f drift.md seeds/1/maps.png seeds/1/trajectory_groundtruth.tum
          seeds/1/trajectory_odometry.tum seeds/1/trajectory_heading-drift.tum)
  if(NOT EXISTS "${WORK_DIR}/drift/${f}")
    message(FATAL_ERROR "coopmap bench drift did not write ${f}")
  endif()
endforeach()
if(NOT out MATCHES "\\| heading-drift \\|")
  message(FATAL_ERROR "the summary table is missing:\n${out}")
endif()

# A run's traverse log (the look at the home base, then the first of the route), rebuilt;
# then cut short and rejected clearly.
execute_process(COMMAND "${COOPMAP}" run "${SOURCE_DIR}/worlds/lab.yaml" --robots 1
                        --duration 40 --out "${WORK_DIR}/run" --quiet
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "coopmap run failed:\n${err}")
endif()
set(log "${WORK_DIR}/run/traverse_jose.traverse")
execute_process(COMMAND "${COOPMAP}" traverse "${log}" --out "${WORK_DIR}/t"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "jose: [0-9]+ entries" OR NOT EXISTS "${WORK_DIR}/t/map.pgm")
  message(FATAL_ERROR "coopmap traverse failed on a good log (${rc}):\n${out}${err}")
endif()
# Its stretches aligned to the map rebuilt from it: one CSV row per stretch, and the
# summary counts them (entries / 6, rounded down).
execute_process(COMMAND "${COOPMAP}" traverse "${log}" --out "${WORK_DIR}/ta" --align-stretch 6
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "jose: ([0-9]+) entries")
  message(FATAL_ERROR "coopmap traverse --align-stretch failed (${rc}):\n${out}${err}")
endif()
math(EXPR expected "${CMAKE_MATCH_1} / 6")
if(expected LESS 1 OR NOT out MATCHES "stretches of 6 aligned to the map: ([0-9]+) of ${expected};")
  message(FATAL_ERROR "expected ${expected} stretches of 6 in the summary:\n${out}")
endif()
file(STRINGS "${WORK_DIR}/ta/stretches.csv" rows)
list(LENGTH rows n)
math(EXPR n "${n} - 1")
list(GET rows 0 header)
if(NOT n EQUAL expected OR NOT header MATCHES "^first_entry,x,y,theta_deg,.*,moved_m,turned_deg$")
  message(FATAL_ERROR "stretches.csv: expected a header and ${expected} rows, got:\n${rows}")
endif()
execute_process(COMMAND "${COOPMAP}" traverse "${log}" --out "${WORK_DIR}/tb" --align-stretch -2
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "--align-stretch")
  message(FATAL_ERROR "a negative --align-stretch was not refused clearly (${rc}):\n${err}")
endif()

execute_process(COMMAND "${CMAKE_COMMAND}" -E copy "${log}" "${WORK_DIR}/cut.traverse")
file(SIZE "${log}" size)
math(EXPR cut_size "${size} - 100")
execute_process(COMMAND truncate -s ${cut_size} "${WORK_DIR}/cut.traverse" RESULT_VARIABLE trc)
if(NOT trc EQUAL 0)
  message(FATAL_ERROR "test setup: truncate failed")
endif()
execute_process(COMMAND "${COOPMAP}" traverse "${WORK_DIR}/cut.traverse" --out "${WORK_DIR}/t2"
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "cut\\.traverse: record [0-9]+ at byte [0-9]+: truncated")
  message(FATAL_ERROR "a truncated traverse log was not reported clearly (${rc}):\n${err}")
endif()
if(EXISTS "${WORK_DIR}/t2")
  message(FATAL_ERROR "coopmap traverse wrote outputs for a corrupt log")
endif()
# The run's map rebuilt at its true poses: every radial map placed, scored against the truth.
execute_process(COMMAND "${COOPMAP}" remap "${WORK_DIR}/run" --world "${SOURCE_DIR}/worlds/lab.yaml"
                        --poses groundtruth --out "${WORK_DIR}/remap"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "([0-9]+) radial maps \\(jose\\), ([0-9]+) at their groundtruth poses")
  message(FATAL_ERROR "coopmap remap failed (${rc}):\n${out}${err}")
endif()
if(NOT CMAKE_MATCH_1 EQUAL CMAKE_MATCH_2 OR CMAKE_MATCH_1 LESS 3
   OR NOT out MATCHES "wall_recall 0\\.[0-9]+ false_occupied_rate 0\\.[0-9]+ coverage 0\\.[0-9]+"
   OR NOT out MATCHES "2: 0\\.[0-9]+ 3: 0\\.[0-9]+ 4-5: 0\\.[0-9]+ 6-10: 0\\.[0-9]+ 11\\+: 0\\.[0-9]+"
   OR NOT EXISTS "${WORK_DIR}/remap/map_evaluation.png")
  message(FATAL_ERROR "coopmap remap: expected every radial map placed and the scores:\n${out}")
endif()
# The oracle's parts: "corrected" poses 1 m west of the truth (x is negative here: the map
# frame's origin is the home base, east of the start) are fixed by true positions and not by
# true headings.
file(MAKE_DIRECTORY "${WORK_DIR}/shifted")
file(COPY "${log}" "${WORK_DIR}/run/trajectory_jose_groundtruth.tum" DESTINATION "${WORK_DIR}/shifted")
file(STRINGS "${WORK_DIR}/run/trajectory_jose_groundtruth.tum" truth_lines)
set(shifted "")
foreach(line IN LISTS truth_lines)
  if(line MATCHES "^([^ #]+) -([0-9]+)(\\.[0-9]+) (.*)$")
    math(EXPR west "${CMAKE_MATCH_2} + 1")
    string(APPEND shifted "${CMAKE_MATCH_1} -${west}${CMAKE_MATCH_3} ${CMAKE_MATCH_4}\n")
  endif()
endforeach()
file(WRITE "${WORK_DIR}/shifted/trajectory_jose_corrected.tum" "${shifted}")
foreach(oracle none position along across heading)
  set(args "")
  if(NOT oracle STREQUAL "none")
    set(args --oracle ${oracle})
  endif()
  execute_process(COMMAND "${COOPMAP}" remap "${WORK_DIR}/shifted" --world "${SOURCE_DIR}/worlds/lab.yaml"
                          ${args} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0 OR NOT out MATCHES "wall_recall (0\\.[0-9]+) false_occupied_rate (0\\.[0-9]+)")
    message(FATAL_ERROR "coopmap remap --oracle ${oracle} failed (${rc}):\n${out}${err}")
  endif()
  set(scores_${oracle} "${CMAKE_MATCH_1} ${CMAKE_MATCH_2}")
endforeach()
if(NOT out MATCHES "at their corrected positions with the true headings")
  message(FATAL_ERROR "coopmap remap --oracle heading does not say what it placed:\n${out}")
endif()
# The shift split by the true heading: each part alone moves walls (the robot turns a full
# circle, then drives north), neither is the whole shift (the position oracle's map) nor none
# of it.
foreach(part along across)
  if(scores_${part} STREQUAL scores_none OR scores_${part} STREQUAL scores_position)
    message(FATAL_ERROR "remap --oracle ${part} took all or none of the shift: ${scores_${part}} "
                        "(1 m off ${scores_none}, true positions ${scores_position})")
  endif()
endforeach()
execute_process(COMMAND "${COOPMAP}" remap "${WORK_DIR}/run" --world "${SOURCE_DIR}/worlds/lab.yaml"
                        --poses groundtruth OUTPUT_VARIABLE out)
string(REGEX MATCH "wall_recall (0\\.[0-9]+) false_occupied_rate (0\\.[0-9]+)" found "${out}")
set(scores_truth "${CMAKE_MATCH_1} ${CMAKE_MATCH_2}")
if(NOT scores_position STREQUAL scores_truth OR NOT scores_heading STREQUAL scores_none
   OR scores_none STREQUAL scores_truth)
  message(FATAL_ERROR "remap's oracle took the wrong part of the pose: truth ${scores_truth}, "
                      "1 m off ${scores_none}, true positions ${scores_position}, true headings "
                      "${scores_heading}")
endif()
execute_process(COMMAND "${COOPMAP}" remap "${WORK_DIR}/shifted" --world "${SOURCE_DIR}/worlds/lab.yaml"
                        --oracle speed RESULT_VARIABLE rc ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "--oracle: speed not in")
  message(FATAL_ERROR "a bad --oracle was not reported clearly (${rc}):\n${err}")
endif()
# The 40 s run ended before the robot came home: no radial map has a corrected pose.
execute_process(COMMAND "${COOPMAP}" remap "${WORK_DIR}/run" --world "${SOURCE_DIR}/worlds/lab.yaml"
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "none of the [0-9]+ radial maps has a corrected pose")
  message(FATAL_ERROR "a run without corrected poses was not reported clearly (${rc}):\n${err}")
endif()
# A corrupt trajectory line is named by file and line, and nothing is written.
file(MAKE_DIRECTORY "${WORK_DIR}/bad_run")
file(COPY "${log}" DESTINATION "${WORK_DIR}/bad_run")
file(WRITE "${WORK_DIR}/bad_run/trajectory_jose_groundtruth.tum" "# truth\n0 1 2 0 0 0 0 1\n0.1 1 2\n")
execute_process(COMMAND "${COOPMAP}" remap "${WORK_DIR}/bad_run" --world "${SOURCE_DIR}/worlds/lab.yaml"
                        --poses groundtruth --out "${WORK_DIR}/bad_remap"
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "trajectory_jose_groundtruth\\.tum:3: expected 8 numbers"
   OR EXISTS "${WORK_DIR}/bad_remap")
  message(FATAL_ERROR "a corrupt trajectory was not reported clearly (${rc}):\n${err}")
endif()
message(STATUS "drift benchmark outputs and traverse log errors are as documented")
