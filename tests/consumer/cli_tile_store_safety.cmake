cmake_minimum_required(VERSION 3.25)
# The tile store of a tiled lidarfx water run deletes and trusts only what lidarfx wrote:
#  1. OUT/.lidarfx-tiles a symlink to someone's folder: exit 2, that folder's files byte for byte as they were;
#  2. tiles altered after a killed run (a bit flipped, a neighbour's copy, a symlink to a neighbour, a FIFO) are
#     named on stderr and recomputed: the resumed run's files are the untiled run's, byte for byte, and it does
#     not hang on the FIFO (timeout);
#  3. an input edited in place with its size and modification time kept: the resumed run starts over;
#  4. a write that fails (a file size limit, as a full disk) ends the run with the system's reason, non-zero,
#     and leaves no temporary file.
# -DLIDARFX=<lidarfx> -DMAKE_SURVEY=<make_water_survey> -DWORK_DIR=<scratch folder>
include("${CMAKE_CURRENT_LIST_DIR}/make_water_survey.cmake")
set(untiled "${WORK_DIR}/untiled")
execute_process(COMMAND "${LIDARFX}" water "${WORK_DIR}/survey" --cell 2 --out "${untiled}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "untiled lidarfx water failed (${rc}):\n${out}\n${err}")
endif()
file(GLOB outputs RELATIVE "${untiled}" "${untiled}/*")
list(REMOVE_ITEM outputs manifest.json .lidarfx.lock)

function(same_as_untiled dir what)
    foreach(f IN LISTS outputs)
        file(SHA256 "${untiled}/${f}" want)
        file(SHA256 "${dir}/${f}" got)
        if(NOT want STREQUAL got)
            message(FATAL_ERROR "${what}: ${f} differs from the untiled run's")
        endif()
    endforeach()
endfunction()

# 1. The tile store's name is a symlink to a folder of someone's files.
set(theirs "${WORK_DIR}/theirs")
set(linked "${WORK_DIR}/linked")
file(MAKE_DIRECTORY "${theirs}" "${linked}")
foreach(name tile_0.bin manifest.txt photo.jpg)
    file(WRITE "${theirs}/${name}" "someone's ${name}\n")
endforeach()
file(CREATE_LINK "${theirs}" "${linked}/.lidarfx-tiles" SYMBOLIC)
execute_process(COMMAND "${LIDARFX}" water "${WORK_DIR}/survey" --cell 2 --tile 120 --out "${linked}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
if(NOT rc EQUAL 2 OR NOT err MATCHES "is a symbolic link")
    message(FATAL_ERROR "a symlinked tile store: expected exit 2 naming the link, got ${rc}:\n${err}")
endif()
file(GLOB left RELATIVE "${theirs}" "${theirs}/*")
list(SORT left)
if(NOT left STREQUAL "manifest.txt;photo.jpg;tile_0.bin")
    message(FATAL_ERROR "the linked folder now holds: ${left}")
endif()
foreach(name tile_0.bin manifest.txt photo.jpg)
    file(READ "${theirs}/${name}" text)
    if(NOT text STREQUAL "someone's ${name}\n")
        message(FATAL_ERROR "the linked folder's ${name} was changed")
    endif()
endforeach()

# 2. Tiles altered between a killed run and its resumption.
set(tiled "${WORK_DIR}/tiled")
execute_process(COMMAND ${CMAKE_COMMAND} -E env LIDARFX_TEST_KILL_AFTER_TILES=8
                        "${LIDARFX}" water "${WORK_DIR}/survey" --cell 2 --tile 120 --threads 2 --out "${tiled}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
file(GLOB recorded "${tiled}/.lidarfx-tiles/tile_*.bin")
list(LENGTH recorded n)
if(rc EQUAL 0 OR n LESS 8)
    message(FATAL_ERROR "the killed run (${rc}) recorded ${n} tiles, expected at least 8:\n${err}")
endif()
list(SORT recorded)
list(GET recorded 0 flipped)
list(GET recorded 1 copied)
list(GET recorded 2 neighbour)
list(GET recorded 3 linked_tile)
list(GET recorded 4 fifo)
# One bit of a height: the byte at the middle of the file, xor 0x01 (read as hex, written back by printf).
file(SIZE "${flipped}" size)
math(EXPR middle "${size} / 2")
execute_process(COMMAND sh -c "b=$(od -An -tu1 -j ${middle} -N1 '${flipped}' | tr -d ' '); printf \"\\\\$(printf %o $((b ^ 1)))\" | dd of='${flipped}' bs=1 seek=${middle} conv=notrunc 2>/dev/null"
                RESULT_VARIABLE rc)
file(COPY_FILE "${neighbour}" "${copied}")
file(REMOVE "${linked_tile}" "${fifo}")
file(CREATE_LINK "${neighbour}" "${linked_tile}" SYMBOLIC)
execute_process(COMMAND mkfifo "${fifo}" RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "mkfifo failed")
endif()
execute_process(COMMAND "${LIDARFX}" water "${WORK_DIR}/survey" --cell 2 --tile 120 --threads 2 --out "${tiled}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "the resumed run over altered tiles failed (${rc}):\n${err}")
endif()
foreach(why "fails its checksum" "holds tile [0-9]+, not tile" "is a symbolic link, not a regular file" "is a FIFO, not a regular file")
    if(NOT err MATCHES "${why}")
        message(FATAL_ERROR "the resumed run did not say a tile '${why}':\n${err}")
    endif()
endforeach()
same_as_untiled("${tiled}" "resumed over altered tiles")
if(NOT IS_SYMLINK "${linked_tile}" OR NOT EXISTS "${fifo}")
    message(FATAL_ERROR "the symlink or the FIFO at a tile's name was removed or replaced")
endif()
file(REMOVE "${linked_tile}" "${fifo}")

# 3. An input edited in place, its size and modification time kept (touch -r from a copy of the old times).
set(edited "${WORK_DIR}/edited")
execute_process(COMMAND ${CMAKE_COMMAND} -E env LIDARFX_TEST_KILL_AFTER_TILES=4
                        "${LIDARFX}" water "${WORK_DIR}/survey" --cell 2 --tile 120 --threads 2 --out "${edited}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
file(GLOB inputs "${WORK_DIR}/survey/*.las")
list(GET inputs 0 input)
file(SIZE "${input}" size)
math(EXPR near_end "${size} - 7")
execute_process(COMMAND sh -c "touch -r '${input}' '${WORK_DIR}/times' && printf 'Z' | dd of='${input}' bs=1 seek=${near_end} conv=notrunc 2>/dev/null && touch -r '${WORK_DIR}/times' '${input}'"
                RESULT_VARIABLE rc)
execute_process(COMMAND "${LIDARFX}" water "${WORK_DIR}/survey" --cell 2 --tile 120 --threads 2 --out "${edited}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
if(NOT rc EQUAL 0 OR NOT err MATCHES "starting over")
    message(FATAL_ERROR "an input edited in place (size and mtime kept) was not noticed (${rc}):\n${err}")
endif()

# 4. A write that fails: a file size limit (ulimit -f, SIGXFSZ ignored) makes the first tile's write fail
#    (EFBIG) as a full disk does (ENOSPC).
set(full "${WORK_DIR}/full")
execute_process(COMMAND sh -c "trap '' XFSZ; ulimit -f 16; exec '${LIDARFX}' water '${WORK_DIR}/survey' --cell 2 --tile 120 --threads 2 --out '${full}'"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
if(rc EQUAL 0 OR NOT err MATCHES "write failed \\(File too large\\)")
    message(FATAL_ERROR "a failed write: expected a non-zero exit naming the system's reason, got ${rc}:\n${err}")
endif()
file(GLOB_RECURSE temporaries "${full}/*tmp*")
if(temporaries)
    message(FATAL_ERROR "the failed run left temporary files: ${temporaries}")
endif()
message(STATUS "symlinked store refused; 4 altered tiles recomputed to the untiled files; edited input noticed; failed write: ${err}")
