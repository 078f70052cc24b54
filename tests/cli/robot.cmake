# `coopmap robot` against an emulated rFLEX controller (EMULATOR runs a command with the
# emulator on a pseudo-terminal, linked at WORK_DIR/ttyRFLEX): --dry-run checks the base and
# moves nothing; a route is driven and the emulated robot ends where it should; a silent
# controller, a missing device and a malformed config are reported clearly.
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
set(tty "${WORK_DIR}/ttyRFLEX")
set(model "${SOURCE_DIR}/robots/b14/b14.yaml")

file(WRITE "${WORK_DIR}/good.yaml" "model: ${model}
serial:
  device: ${tty}
  baud: 115200
rflex:
  report_period: 0.02
  watchdog_timeout: 1.0
  startup_timeout: 1.0
route:
  linear_speed: 0.4
  control_rate: 20
  max_duration: 60
  waypoints:
    - [0.2, 0.0]
")

# --dry-run: the controller answers, the brake stays on, no motion command is sent.
execute_process(COMMAND "${EMULATOR}" --link "${tty}" -- "${COOPMAP}" robot
                        "${WORK_DIR}/good.yaml" --dry-run
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)
if(NOT rc EQUAL 0 OR NOT out MATCHES "controller answering" OR NOT out MATCHES "nothing moved")
  message(FATAL_ERROR "coopmap robot --dry-run failed (rc ${rc}):\n${out}${err}")
endif()
if(NOT err MATCHES "axis commands 0, brake on")
  message(FATAL_ERROR "coopmap robot --dry-run moved the base:\n${out}${err}")
endif()

# The route: 0.2 m straight ahead, then a stop and the brake.
execute_process(COMMAND "${EMULATOR}" --link "${tty}" -- "${COOPMAP}" robot
                        "${WORK_DIR}/good.yaml"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)
if(NOT rc EQUAL 0 OR NOT out MATCHES "route done: 1 waypoints")
  message(FATAL_ERROR "coopmap robot did not drive the route (rc ${rc}):\n${out}${err}")
endif()
if(NOT err MATCHES "emulator: pose 0\\.(1[5-9]|2[0-4])[0-9] -?0\\.0[0-2][0-9] " OR
   NOT err MATCHES "brake on")
  message(FATAL_ERROR "the emulated robot did not end 0.2 m ahead, braked:\n${out}${err}")
endif()

# Ctrl-C on a long route: a safe stop (the base at rest, brake on) and exit code 130.
file(WRITE "${WORK_DIR}/long.yaml" "model: ${model}
serial: {device: ${tty}}
rflex: {report_period: 0.02, watchdog_timeout: 1.0}
route: {linear_speed: 0.3, control_rate: 20, waypoints: [[5.0, 0.0]]}
")
execute_process(COMMAND "${EMULATOR}" --link "${tty}" --interrupt-after 0.7 -- "${COOPMAP}"
                        robot "${WORK_DIR}/long.yaml"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)
if(NOT rc EQUAL 130 OR NOT out MATCHES "interrupted: stop sent")
  message(FATAL_ERROR "Ctrl-C did not end the route with a stop (rc ${rc}):\n${out}${err}")
endif()
if(NOT err MATCHES "emulator: pose 0\\.[0-9]+ [-0-9.]+ [-0-9.]+, speed 0\\.000, .*brake on")
  message(FATAL_ERROR "the base was not at rest with the brake on after Ctrl-C:\n${out}${err}")
endif()

# A controller that never answers.
execute_process(COMMAND "${EMULATOR}" --link "${tty}" --silent -- "${COOPMAP}" robot
                        "${WORK_DIR}/good.yaml" --dry-run
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)
if(rc EQUAL 0 OR NOT err MATCHES "no odometry report from the rFLEX controller within")
  message(FATAL_ERROR "a silent controller was not reported clearly (rc ${rc}):\n${out}${err}")
endif()

# No device at all.
execute_process(COMMAND "${COOPMAP}" robot "${WORK_DIR}/good.yaml" --dry-run
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)
if(rc EQUAL 0 OR NOT err MATCHES "ttyRFLEX: cannot open")
  message(FATAL_ERROR "a missing device was not reported clearly (rc ${rc}):\n${out}${err}")
endif()

# A malformed config: the error names file, line, column and field; nothing is opened.
file(WRITE "${WORK_DIR}/bad.yaml" "model: ${model}
serial:
  device: ${tty}
  baud: fast
")
execute_process(COMMAND "${COOPMAP}" robot "${WORK_DIR}/bad.yaml" --dry-run
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)
if(NOT rc EQUAL 2 OR NOT err MATCHES "bad\\.yaml:4:9: serial\\.baud: expected a baud rate")
  message(FATAL_ERROR "a malformed config was not reported with file:line (rc ${rc}):\n${err}")
endif()

# A config with neither a mission nor a route is fine for --dry-run only.
file(WRITE "${WORK_DIR}/noroute.yaml" "model: ${model}\nserial: {device: ${tty}}\n")
execute_process(COMMAND "${COOPMAP}" robot "${WORK_DIR}/noroute.yaml"
                RESULT_VARIABLE rc ERROR_VARIABLE err TIMEOUT 60)
if(NOT rc EQUAL 2 OR NOT err MATCHES "nothing to do \\(add a mission with its cameras, or route")
  message(FATAL_ERROR "a config without a route was not reported (rc ${rc}):\n${err}")
endif()
# A mission without cameras, and one with neither a calibration nor rectified sources.
file(WRITE "${WORK_DIR}/blind.yaml" "model: ${model}
serial: {device: ${tty}}
mission: {name: r, map: {origin: [0, 0], resolution: 0.05, width: 10, height: 10}}
")
execute_process(COMMAND "${COOPMAP}" robot "${WORK_DIR}/blind.yaml"
                RESULT_VARIABLE rc ERROR_VARIABLE err TIMEOUT 60)
if(NOT rc EQUAL 2 OR NOT err MATCHES "blind\\.yaml:3:10: mission: a mission needs the cameras")
  message(FATAL_ERROR "a mission without cameras was not reported (rc ${rc}):\n${err}")
endif()
file(WRITE "${WORK_DIR}/unrectified.yaml" "model: ${model}
serial: {device: ${tty}}
cameras: {sources: [a.png, b.png, c.png]}
mission: {name: r, map: {origin: [0, 0], resolution: 0.05, width: 10, height: 10}}
")
execute_process(COMMAND "${COOPMAP}" robot "${WORK_DIR}/unrectified.yaml"
                RESULT_VARIABLE rc ERROR_VARIABLE err TIMEOUT 60)
if(NOT rc EQUAL 2 OR NOT err MATCHES "unrectified\\.yaml:3:10: cameras: expected either 'calibration'")
  message(FATAL_ERROR "cameras without a rectification were not reported (rc ${rc}):\n${err}")
endif()
message(STATUS "coopmap robot checks and drives an emulated B-14 and reports faults clearly")
