# Damaged images (a map's, a recorded frame) are reported by coopmap alone: exit 2 and one
# line on stderr, "coopmap: <file>: <what is wrong>", no libpng or OpenCV text before it.
include("${CMAKE_CURRENT_LIST_DIR}/helpers.cmake")
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

# One line on stderr, coopmap's own.
function(expect_one_line what pattern)
  expect_exit2("${what}" "^coopmap: ${pattern}\n$" ${ARGN})
endfunction()

record_lab("${WORK_DIR}/rec" "${WORK_DIR}/live")

set(yaml "resolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n")
# A PNG cut short, a PNG with a flipped byte, a PGM with too few pixels, a missing image.
foreach(name cut flipped short missing)
  file(WRITE "${WORK_DIR}/${name}.yaml" "image: ${name}.img\n${yaml}")
endforeach()
file(WRITE "${WORK_DIR}/short.img" "P5\n10 10\n255\nabc")
execute_process(COMMAND bash -c "head -c 200 \"$0\" > \"$1\"" "${WORK_DIR}/live/map_jose.png"
                        "${WORK_DIR}/cut.img")
execute_process(COMMAND bash -c "cp \"$0\" \"$1\" && printf '\\x55' | dd of=\"$1\" bs=1 seek=60 conv=notrunc status=none"
                        "${WORK_DIR}/live/map_jose.png" "${WORK_DIR}/flipped.img")
expect_one_line("a PNG cut short" ".*cut\\.img: truncated: [^\n]*\\(the map image named in [^\n]*cut\\.yaml\\)"
                corners "${WORK_DIR}/cut.yaml" --out "${WORK_DIR}/o1")
expect_one_line("a damaged PNG" ".*flipped\\.img: damaged: chunk 'IDAT' at byte [0-9]+: checksum mismatch[^\n]*"
                corners "${WORK_DIR}/flipped.yaml" --out "${WORK_DIR}/o2")
expect_one_line("a PGM cut short" ".*short\\.img: truncated: 3 bytes of pixels, 100 expected[^\n]*"
                corners "${WORK_DIR}/short.yaml" --out "${WORK_DIR}/o3")
expect_one_line("a missing image" ".*missing\\.img: cannot open the image[^\n]*"
                corners "${WORK_DIR}/missing.yaml" --out "${WORK_DIR}/o4")

# A recorded frame cut short.
execute_process(COMMAND bash -c "head -c 100 \"$0\" > \"$0.cut\" && mv \"$0.cut\" \"$0\""
                        "${WORK_DIR}/rec/jose/images/000000_horizontal.png")
expect_one_line("a recorded frame cut short"
                ".*000000_horizontal\\.png: frame 0: truncated: [^\n]*"
                replay "${WORK_DIR}/rec" --out "${WORK_DIR}/o5")
message(STATUS "damaged images are reported by coopmap alone")
