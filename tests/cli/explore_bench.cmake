# `coopmap bench explore`: a row per generated world with its seed and scores, the summary
# naming the worst worlds; a run that fails is reported in its row and the benchmark goes
# on; bad options exit with code 2 and a message naming the option. One robot on the same
# worlds, and two robots against one (`bench speedup`).
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

execute_process(COMMAND "${COOPMAP}" bench explore --first-seed 1 --count 2 --duration 20
                        --jobs 2 --out "${WORK_DIR}/b"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "coopmap bench explore failed (${rc}):\n${out}${err}")
endif()
foreach(seed 1 2)
  if(NOT err MATCHES "seed ${seed} \\([a-z]+\\): coverage [0-9.]+, [0-9.]+ s wall")
    message(FATAL_ERROR "no progress line for seed ${seed}:\n${err}")
  endif()
  foreach(f worlds/world_${seed}.yaml runs/${seed}/metrics.json runs/${seed}.log
            runs/${seed}.events)
    if(NOT EXISTS "${WORK_DIR}/b/${f}")
      message(FATAL_ERROR "coopmap bench explore did not write ${f}")
    endif()
  endforeach()
  file(READ "${WORK_DIR}/b/runs/${seed}.events" events)
  if(NOT events MATCHES "jose: path [0-9.]+ m, [0-9]+ frames")
    message(FATAL_ERROR "runs/${seed}.events holds no summary of jose's run:\n${events}")
  endif()
endforeach()
file(STRINGS "${WORK_DIR}/b/explore.csv" rows)
list(LENGTH rows n)
if(NOT n EQUAL 3)
  message(FATAL_ERROR "explore.csv: expected a header and 2 rows, got:\n${rows}")
endif()
list(GET rows 0 header)
set(expected_header "seed,run_seed,family,floor_area_m2,robots,coverage,time_to_50_s,time_to_90_s,\
wall_recall,false_occupied_rate,contacts,robot1,ending1,reason1,robot2,ending2,reason2,\
exploration_complete,wall_time_s")
if(NOT header STREQUAL expected_header)
  message(FATAL_ERROR "explore.csv header:\n${header}\nexpected:\n${expected_header}")
endif()
foreach(seed 1 2)
  list(GET rows ${seed} row)
  # seed, family, area in [100, 600] (and its rounding), 2 robots, coverage in [0, 1],
  # times, wall recall and false-occupied in [0, 1], contacts, jose's and eric's endings.
  if(NOT row MATCHES "^${seed},${seed},(corridor|lt|loop|open),([0-9]+)\\.[0-9],2,(0\\.[0-9]+|1\\.0+),(-1|[0-9]+),(-1|[0-9]+),(0\\.[0-9]+|1\\.0+),0\\.[0-9]+,[0-9]+,jose,([^,]+),\"[^\"]*\",eric,([^,]+),\"[^\"]*\",(true|false),[0-9]+\\.[0-9]$")
    message(FATAL_ERROR "explore.csv row ${seed} is not plausible:\n${row}")
  endif()
  if(CMAKE_MATCH_2 LESS 99 OR CMAKE_MATCH_2 GREATER 600 OR CMAKE_MATCH_6 STREQUAL "failed"
     OR CMAKE_MATCH_7 STREQUAL "failed")
    message(FATAL_ERROR "explore.csv row ${seed}: area or ending not plausible:\n${row}")
  endif()
endforeach()
file(READ "${WORK_DIR}/b/explore.md" md)
foreach(seed 1 2)
  if(NOT md MATCHES "\\| ${seed} \\| [a-z]+ \\|[^\n]*\\[map\\]\\(runs/${seed}/shared_map_evaluation\\.png\\)")
    message(FATAL_ERROR "explore.md does not list world ${seed} with its map:\n${md}")
  endif()
endforeach()
if(NOT md MATCHES "\\| all four \\| [0-2] \\|")
  message(FATAL_ERROR "explore.md does not count the targets:\n${md}")
endif()

# One robot on the same worlds, and two robots against one (`bench speedup`): both worlds
# compared; a two-robot output given as the one-robot one is refused, naming its file.
execute_process(COMMAND "${COOPMAP}" bench explore --first-seed 1 --count 2 --duration 20
                        --robots 1 --jobs 2 --quiet --out "${WORK_DIR}/one"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
file(STRINGS "${WORK_DIR}/one/explore.csv" rows)
list(GET rows 1 row)
if(NOT rc EQUAL 0 OR NOT row MATCHES "^1,1,[a-z]+,[0-9.]+,1,[0-9.]+,.*,jose,")
  message(FATAL_ERROR "coopmap bench explore --robots 1 failed (${rc}):\n${out}${err}\n${row}")
endif()
execute_process(COMMAND "${COOPMAP}" bench speedup --two "${WORK_DIR}/b" --one "${WORK_DIR}/one"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "sooner in [0-2] of 2 worlds"
   OR NOT out MATCHES "\\| 2 \\| generated_[a-z]+_2 \\| ")
  message(FATAL_ERROR "coopmap bench speedup (${rc}):\n${out}${err}")
endif()
execute_process(COMMAND "${COOPMAP}" bench speedup --two "${WORK_DIR}/b" --one "${WORK_DIR}/b"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 2 OR NOT err MATCHES "runs/1/metrics.json: expected a run of 1 robot, got 2")
  message(FATAL_ERROR "bench speedup took two robots for one (${rc}):\n${out}${err}")
endif()

# The same world with other noise: the run's seed is the world's plus the offset, in the
# row, the run's metrics.json and the command explore.md gives to run it again.
execute_process(COMMAND "${COOPMAP}" bench explore --first-seed 3 --count 1 --duration 10
                        --run-seed-offset 100 --quiet --out "${WORK_DIR}/o"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "coopmap bench explore --run-seed-offset failed (${rc}):\n${out}${err}")
endif()
file(STRINGS "${WORK_DIR}/o/explore.csv" rows)
list(GET rows 1 row)
file(READ "${WORK_DIR}/o/runs/3/metrics.json" metrics)
file(READ "${WORK_DIR}/o/explore.md" md)
if(NOT row MATCHES "^3,103," OR NOT metrics MATCHES "\"seed\": 103[,\n]"
   OR NOT md MATCHES "world_<seed>\\.yaml --seed <seed> \\+ 100 ")
  message(FATAL_ERROR "--run-seed-offset 100 did not run world 3 with seed 103:\n${row}\n${md}")
endif()

# A folder of other files is not the benchmark's to replace: refused before any work.
file(MAKE_DIRECTORY "${WORK_DIR}/f/runs")
file(WRITE "${WORK_DIR}/f/runs/3" "in the way")
function(expect_rejected pattern)
  execute_process(COMMAND "${COOPMAP}" bench explore ${ARGN}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 2 OR NOT err MATCHES "${pattern}")
    message(FATAL_ERROR "'bench explore ${ARGN}' was not rejected clearly (rc ${rc}):\n${out}${err}")
  endif()
endfunction()
expect_rejected("--robots: expected 1 or 2, got 3" --robots 3 --out "${WORK_DIR}/r")
expect_rejected("--count: expected at least 1, got 0" --count 0 --out "${WORK_DIR}/r")
expect_rejected("--duration: expected a positive number of seconds, got 0" --duration 0
                --out "${WORK_DIR}/r")
expect_rejected("--jobs: expected at least 1, got 0" --jobs 0 --out "${WORK_DIR}/r")
expect_rejected("--out: expected an empty folder or one coopmap wrote" --out "${WORK_DIR}/f")
expect_rejected("--out: expected a folder to write to" --out "${WORK_DIR}/f/runs/3/x")
if(EXISTS "${WORK_DIR}/r")
  message(FATAL_ERROR "a rejected 'bench explore' wrote ${WORK_DIR}/r")
endif()
message(STATUS "exploration benchmark outputs and errors are as documented")
