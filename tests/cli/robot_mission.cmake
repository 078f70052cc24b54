# `coopmap robot` with a mission, end to end: the robot's agent drives the emulated rFLEX
# controller (EMULATOR runs the command with the emulator on a pseudo-terminal, linked at
# WORK_DIR/ttyRFLEX) while the cameras read a recorded image sequence (rectified, as a camera
# head that rectifies itself gives them): the agent looks at the home base and places itself,
# explores, its commands reach the emulator, it comes home and looks at the home base to end
# its first sortie, and its map and traverse log are written. The images come from a
# simulated run of the same mission, so what the cameras see and where the emulated base goes
# agree as far as the two bases move alike: on the wall clock they part, and how far decides
# whether the look at home finds a fix (the fixes themselves are the scenario tests'). Runs on
# the wall clock: about 110 s.
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
set(settings "--first-sortie-budget-m" "0.6" "--sortie-budget-m" "0.6" "--max-sorties" "2")
execute_process(COMMAND "${COOPMAP}" run "${SOURCE_DIR}/worlds/lab.yaml" --robots 1 --explore
                        --duration 140 ${settings} --record "${WORK_DIR}/rec"
                        --out "${WORK_DIR}/sim" --quiet
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "recording the image sequence failed (rc ${rc}):\n${out}${err}")
endif()

set(tty "${WORK_DIR}/ttyRFLEX")
file(WRITE "${WORK_DIR}/robot.yaml" "model: ${SOURCE_DIR}/robots/b14/b14.yaml
serial: {device: ${tty}}
rflex: {report_period: 0.02, watchdog_timeout: 1.0, startup_timeout: 2.0}
cameras:
  sources: [rec/jose/images/%06d_reference.png, rec/jose/images/%06d_horizontal.png,
            rec/jose/images/%06d_vertical.png]
  rectified: true
mission:
  name: jose
  mode: explore
  map: {origin: [-4, -3], resolution: 0.05, width: 240, height: 200}
  settings: {first_sortie_budget_m: 0.6, sortie_budget_m: 0.6, max_sorties: 2}
control_rate: 20
max_duration: 110
")
execute_process(COMMAND "${EMULATOR}" --link "${tty}" -- "${COOPMAP}" robot
                        "${WORK_DIR}/robot.yaml" --out "${WORK_DIR}/out"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 300)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "coopmap robot's mission failed (rc ${rc}):\n${out}${err}")
endif()
if(NOT out MATCHES "explore mission of jose")
  message(FATAL_ERROR "coopmap robot did not start the mission:\n${out}${err}")
endif()
if(NOT out MATCHES "placed by the home base")
  message(FATAL_ERROR "the agent did not place itself by the home base:\n${out}${err}")
endif()
# Home, it looks at the home base: the sortie ends there, fixed, or (where the emulated base
# and the recorded images have parted) the look finds no fix it trusts and is taken again.
if(NOT out MATCHES "(sortie 1 at [0-9]+ s: [0-9]+ scans, |fix from the look at [0-9]+ s)")
  message(FATAL_ERROR "the agent came home to no look at the home base:\n${out}${err}")
endif()
if(NOT err MATCHES "axis commands ([0-9]+)" OR CMAKE_MATCH_1 LESS 50)
  message(FATAL_ERROR "the agent's commands did not reach the emulated base:\n${out}${err}")
endif()
if(NOT out MATCHES "([0-9]+) frames, odometry" OR CMAKE_MATCH_1 LESS 150)
  message(FATAL_ERROR "the agent mapped too few frames:\n${out}${err}")
endif()
foreach(f map_jose.pgm map_jose.yaml map_jose.png traverse_jose.traverse
          trajectory_jose_odometry.tum)
  if(NOT EXISTS "${WORK_DIR}/out/${f}")
    message(FATAL_ERROR "coopmap robot --out did not write ${f}:\n${out}")
  endif()
endforeach()
message(STATUS "coopmap robot ran the mission on the emulated base:\n${out}")
