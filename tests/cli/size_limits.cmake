# Sizes read from input are checked against coopmap's map size limit (core/mapping/grid.h)
# before anything is allocated: a 4 km floor, a 100000 x 100000 map in a recording, a 20000 x
# 20000 map image, a traverse log mapped at 1e-9 m per cell. Each is refused with exit 2,
# naming the file and field, and nothing is written.
include("${CMAKE_CURRENT_LIST_DIR}/helpers.cmake")
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

function(expect_refused what pattern)
  expect_exit2("${what}" "${pattern}" ${ARGN})
  if(EXISTS "${WORK_DIR}/out")
    message(FATAL_ERROR "${what}: outputs were written")
  endif()
endfunction()

file(READ "${SOURCE_DIR}/worlds/lab.yaml" lab)
string(REPLACE "floor: {min: [0, 0], max: [10, 8]" "floor: {min: [0, 0], max: [4000, 4000]"
               huge "${lab}")
if(huge STREQUAL lab)
  message(FATAL_ERROR "test setup: the floor line was not found in worlds/lab.yaml")
endif()
set(world "${SOURCE_DIR}/worlds/.huge_for_test.yaml")
file(WRITE "${world}" "${huge}")
expect_refused("a 4 km floor"
  "\\.huge_for_test\\.yaml:[0-9]+:[0-9]+: floor: the floor at map_resolution 0.05 m: expected a grid of at most 8192 x 8192"
  run "${world}" --duration 1 --quiet --out "${WORK_DIR}/out")
file(REMOVE "${world}")

# A recording whose map is 100000 x 100000 cells.
record_lab("${WORK_DIR}/rec" "${WORK_DIR}/live")
file(READ "${WORK_DIR}/rec/dataset.yaml" dataset)
string(REGEX REPLACE "width: [0-9]+" "width: 100000" dataset "${dataset}")
string(REGEX REPLACE "height: [0-9]+" "height: 100000" dataset "${dataset}")
file(WRITE "${WORK_DIR}/rec/dataset.yaml" "${dataset}")
expect_refused("a 100000 x 100000 recorded map"
  "dataset\\.yaml:[0-9]+:[0-9]+: map\\.height: expected a grid of at most 8192 x 8192 = 67108864 cells, got 100000 x 100000"
  replay "${WORK_DIR}/rec" --out "${WORK_DIR}/out")

# A map image that says it is 20000 x 20000 (only its header is read).
file(WRITE "${WORK_DIR}/big.pgm" "P5\n20000 20000\n255\n")
file(WRITE "${WORK_DIR}/big.yaml"
     "image: big.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n")
expect_refused("a 20000 x 20000 map image"
  "big\\.pgm: expected an image of at most 67108864 pixels, got 20000 x 20000 \\(the map image named in .*big\\.yaml\\)"
  corners "${WORK_DIR}/big.yaml" --out "${WORK_DIR}/out")

expect_refused("a traverse log at 1e-9 m per cell"
  "--resolution: the map of .*traverse_jose\\.traverse at 1e-09 m per cell would be larger than a grid of at most 8192 x 8192"
  traverse "${WORK_DIR}/live/traverse_jose.traverse" --resolution 1e-9 --out "${WORK_DIR}/out")
message(STATUS "sizes are checked before anything is allocated")
