# Included by the command-line tests: expect_same_files(<reference folder> <folder> <what>) fails with
# "<what>: <file> differs from the untiled run's" unless every output of the reference run (manifest.json and the
# lock excepted: the manifest records the command line) has the same bytes in <folder>, and the tile folder
# <folder>/.lidarfx-tiles is gone.
function(expect_same_files reference dir what)
    file(GLOB outputs RELATIVE "${reference}" "${reference}/*")
    list(REMOVE_ITEM outputs manifest.json .lidarfx.lock)
    foreach(f IN LISTS outputs)
        file(SHA256 "${reference}/${f}" want)
        file(SHA256 "${dir}/${f}" got)
        if(NOT want STREQUAL got)
            message(FATAL_ERROR "${what}: ${f} differs from the untiled run's")
        endif()
    endforeach()
    if(EXISTS "${dir}/.lidarfx-tiles")
        message(FATAL_ERROR "${what}: the tile folder outlived the complete run")
    endif()
endfunction()
