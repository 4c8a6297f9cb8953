# SPDX-License-Identifier: Apache-2.0
# The layering rule of docs/architecture.md, checked from the #include lines of every header under
# ${INCLUDE_DIR}/lidarfx: a header includes lidarfx headers only from its own folder or from a lower layer.
#   layer 0  core/
#   layer 1  adapters/ and kernels/<area>/   (kernel areas never include each other)
#   layer 2  pipelines/<area>/               (pipelines never include each other): water, solar, buildings
#   layer 3  tiling/
# An area's detail/ folder (e.g. kernels/filter/detail/) belongs to its area: it holds the implementation behind the
# area's public headers, which the umbrella does not include directly.
# lidarfx.hpp (the umbrella) may include anything. A folder that is not in this table fails the check, so a new
# module has to be placed in a layer (here and in docs/architecture.md) before it can exist.
# Usage: cmake -DINCLUDE_DIR=<dir holding lidarfx/> -P check_layers.cmake
# Each violation is reported as "<header>:<line>: <the include line>  (<why>)"; the script then fails.
if(NOT INCLUDE_DIR)
    message(FATAL_ERROR "check_layers.cmake: pass -DINCLUDE_DIR=<folder holding lidarfx/>")
endif()

# Sets <out_layer> to the layer of folder <dir> (path below lidarfx/, e.g. "kernels/filter"), -1 if unknown.
function(layer_of dir out_layer)
    if(dir STREQUAL "core")
        set(layer 0)
    elseif(dir STREQUAL "adapters" OR dir MATCHES "^kernels/[a-z_]+$")
        set(layer 1)
    elseif(dir MATCHES "^pipelines/[a-z_]+$")
        set(layer 2)
    elseif(dir STREQUAL "tiling")
        set(layer 3)
    else()
        set(layer -1)
    endif()
    set(${out_layer} ${layer} PARENT_SCOPE)
endfunction()

get_filename_component(INCLUDE_DIR "${INCLUDE_DIR}" ABSOLUTE)
file(GLOB_RECURSE headers RELATIVE "${INCLUDE_DIR}/lidarfx" "${INCLUDE_DIR}/lidarfx/*.hpp")
list(SORT headers)
set(violations "")
set(includes_checked 0)
foreach(header IN LISTS headers)
    if(header STREQUAL "lidarfx.hpp")
        continue()
    endif()
    get_filename_component(dir "${header}" DIRECTORY)
    string(REGEX REPLACE "/detail$" "" dir "${dir}")  # <area>/detail/ holds the area's implementation
    layer_of("${dir}" layer)
    if(layer EQUAL -1)
        string(APPEND violations "\nlidarfx/${header}:1: folder '${dir}' has no layer (add it to docs/architecture.md and tests/layering/check_layers.cmake)")
        continue()
    endif()
    file(STRINGS "${INCLUDE_DIR}/lidarfx/${header}" lines)
    set(number 0)
    foreach(line IN LISTS lines)
        math(EXPR number "${number} + 1")
        if(NOT line MATCHES "^[ \t]*#[ \t]*include[ \t]*[<\"]lidarfx/([^>\"]+)[>\"]")
            continue()
        endif()
        math(EXPR includes_checked "${includes_checked} + 1")
        set(target "${CMAKE_MATCH_1}")
        get_filename_component(target_dir "${target}" DIRECTORY)
        string(REGEX REPLACE "/detail$" "" target_dir "${target_dir}")
        layer_of("${target_dir}" target_layer)
        set(why "")
        if(target STREQUAL "lidarfx.hpp")
            set(why "the umbrella header is for hosts, not for the library's own headers")
        elseif(target_layer EQUAL -1)
            set(why "'${target_dir}' is not a layer of the library")
        elseif(target_dir STREQUAL dir)
            # own folder: allowed
        elseif(target_layer EQUAL layer)
            set(why "sideways: ${dir} and ${target_dir} are both layer ${layer}; move what both need down a layer")
        elseif(target_layer GREATER layer)
            set(why "upwards: ${dir} is layer ${layer}, ${target_dir} is layer ${target_layer}")
        endif()
        if(why)
            string(STRIP "${line}" shown)
            string(APPEND violations "\nlidarfx/${header}:${number}: ${shown}  (${why})")
        endif()
    endforeach()
endforeach()

# The umbrella header includes every public header but adapters/ (they need third-party headers).
if(EXISTS "${INCLUDE_DIR}/lidarfx/lidarfx.hpp")
    file(READ "${INCLUDE_DIR}/lidarfx/lidarfx.hpp" umbrella)
    foreach(header IN LISTS headers)
        if(header STREQUAL "lidarfx.hpp" OR header MATCHES "^adapters/" OR header MATCHES "/detail/")
            continue()
        endif()
        string(FIND "${umbrella}" "\"lidarfx/${header}\"" at)
        if(at EQUAL -1)
            string(APPEND violations "\nlidarfx/lidarfx.hpp:1: does not include lidarfx/${header}")
        endif()
    endforeach()
endif()

list(LENGTH headers count)
if(count EQUAL 0)
    message(FATAL_ERROR "no header found under ${INCLUDE_DIR}/lidarfx")
endif()
if(violations)
    message(FATAL_ERROR "layering violations:${violations}")
endif()
message(STATUS "layering holds: ${count} headers, ${includes_checked} lidarfx includes checked")
