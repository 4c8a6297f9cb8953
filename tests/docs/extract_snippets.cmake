# SPDX-License-Identifier: Apache-2.0
# Turns the code of Markdown pages into one doctest source file, so that the docs cannot drift from the library:
#   cmake -DOUTPUT=<file.cpp> -DDOCS=<page.md,...> [-DSTAMP=<file>] -P extract_snippets.cmake
#
# - Every ```cpp block becomes a TEST_CASE named "<page>:<line>". A block is a list of statements (run inside the
#   test case), unless it has a line starting with "int main(": then it is a whole program, placed in its own
#   namespace, and the test case runs its main() and checks that it returns 0. #include lines of every block are
#   moved to the top of the file. #line directives make compiler errors point at the page's own lines.
# - Under a heading "#### `lidarfx::<options struct>`", a table whose rows start "| `<field>` | <default> |" is
#   checked too: the fields, in the table's order, must be the struct's (a designated initializer naming every
#   row compiles only if each field exists and the order is the declaration order), and a default written as
#   `<C++ expression>` must equal the default member's value (NaN: written as NaN, checked with std::isnan).
#   Rows whose default is neither (e.g. "—" for a nested struct) are checked for name and order only.
# Snippets may use doctest's CHECK(condition) as their assertion; a block that is not a whole program may use
# <lidarfx/lidarfx.hpp> and the standard headers listed at the end of this script without including them.
cmake_minimum_required(VERSION 3.25)
if(NOT OUTPUT OR NOT DOCS)
    message(FATAL_ERROR "usage: cmake -DOUTPUT=<file.cpp> -DDOCS=<page.md,...> [-DSTAMP=<file>] -P extract_snippets.cmake")
endif()
string(REPLACE "," ";" DOCS "${DOCS}")

# CMake lists split at ';' and treat '[' ']' specially: mask them while the text is handled as a list of lines.
function(mask_text text out)
    string(REPLACE ";" "@LFX_SEMI@" text "${text}")
    string(REPLACE "[" "@LFX_LB@" text "${text}")
    string(REPLACE "]" "@LFX_RB@" text "${text}")
    string(REPLACE "\\" "@LFX_BS@" text "${text}")
    set(${out} "${text}" PARENT_SCOPE)
endfunction()
function(unmask_text text out)
    string(REPLACE "@LFX_SEMI@" ";" text "${text}")
    string(REPLACE "@LFX_LB@" "[" text "${text}")
    string(REPLACE "@LFX_RB@" "]" text "${text}")
    string(REPLACE "@LFX_BS@" "\\" text "${text}")
    set(${out} "${text}" PARENT_SCOPE)
endfunction()

set(includes "")
set(bodies "")
set(snippet_count 0)
set(table_count 0)
foreach(page IN LISTS DOCS)
    get_filename_component(page_name "${page}" NAME)
    file(READ "${page}" text)
    mask_text("${text}" text)
    string(REPLACE "\n" ";" lines "${text}")
    set(line_no 0)
    set(in_block OFF)
    set(struct_name "")
    foreach(line IN LISTS lines)
        math(EXPR line_no "${line_no} + 1")
        if(in_block)
            if(line MATCHES "^```[ \t]*$")
                set(in_block OFF)
                math(EXPR snippet_count "${snippet_count} + 1")
                set(name "${page_name}:${block_start}")
                if(is_program)
                    string(APPEND bodies "namespace snippet_${snippet_count} {\n#line ${block_first} \"${page}\"\n"
                        "${block}\n}  // namespace snippet_${snippet_count}\n"
                        "TEST_CASE(\"${name}\") { CHECK(snippet_${snippet_count}::main() == 0); }\n\n")
                else()
                    string(APPEND bodies "TEST_CASE(\"${name}\") {\n#line ${block_first} \"${page}\"\n${block}\n}\n\n")
                endif()
            else()
                if(line MATCHES "^#include")
                    list(APPEND includes "${line}")
                    set(line "")  # keeps the line numbers of what follows
                endif()
                if(line MATCHES "^int main\\(")
                    set(is_program ON)
                endif()
                string(APPEND block "${line}\n")
            endif()
            continue()
        endif()
        if(line MATCHES "^```cpp[ \t]*$")
            set(in_block ON)
            set(is_program OFF)
            set(block "")
            set(block_start ${line_no})
            math(EXPR block_first "${line_no} + 1")
            continue()
        endif()
        # Options tables: a heading names the struct, the rows that follow name its fields in order.
        if(line MATCHES "^#+ ")
            if(struct_name AND fields)
                math(EXPR table_count "${table_count} + 1")
                string(APPEND bodies "TEST_CASE(\"${page_name}:${struct_line}: ${struct_name}\") {\n"
                    "    using namespace lidarfx;\n    const ${struct_name} defaults{};\n"
                    "    [[maybe_unused]] const ${struct_name} in_order{${designated}};\n${checks}}\n\n")
            endif()
            set(struct_name "")
            set(fields "")
            if(line MATCHES "^#### `(lidarfx::[a-z_0-9:]+)`")
                set(struct_name "${CMAKE_MATCH_1}")
                set(struct_line ${line_no})
                set(designated "")
                set(checks "")
            endif()
            continue()
        endif()
        if(struct_name AND line MATCHES "^\\| `([a-z_0-9]+)` \\| ([^|]*) \\|")
            set(field "${CMAKE_MATCH_1}")
            string(STRIP "${CMAKE_MATCH_2}" default_cell)
            list(APPEND fields "${field}")
            if(designated)
                string(APPEND designated ", ")
            endif()
            string(APPEND designated ".${field} = defaults.${field}")
            set(default_expr "")
            if(default_cell MATCHES "^`(.*)`$")
                set(default_expr "${CMAKE_MATCH_1}")
            endif()
            if(NOT default_expr STREQUAL "" AND NOT default_expr MATCHES "^{")
                string(APPEND checks "#line ${line_no} \"${page}\"\n"
                    "    CHECK(defaults.${field} == static_cast<decltype(${struct_name}::${field})>(${default_expr}))@LFX_SEMI@\n")
            elseif(default_cell STREQUAL "NaN")
                string(APPEND checks "#line ${line_no} \"${page}\"\n    CHECK(std::isnan(defaults.${field}))@LFX_SEMI@\n")
            endif()
        endif()
    endforeach()
    if(in_block)
        message(FATAL_ERROR "${page}:${block_start}: a ```cpp block is not closed")
    endif()
    if(struct_name AND fields)
        message(FATAL_ERROR "${page}: the options table of ${struct_name} must be followed by a heading")
    endif()
endforeach()


list(REMOVE_DUPLICATES includes)
list(SORT includes)
string(REPLACE ";" "\n" include_lines "${includes}")
# A block that is not a whole program may use the umbrella header and these standard headers without naming them.
string(CONCAT source "// Generated by tests/docs/extract_snippets.cmake from the Markdown pages; edit the pages, not this file.\n"
    "#include <doctest/doctest.h>\n\n"
    "#include <array>\n#include <chrono>\n#include <cmath>\n#include <cstddef>\n#include <cstdint>\n#include <cstdio>\n"
    "#include <cstring>\n#include <limits>\n#include <optional>\n#include <span>\n#include <string>\n#include <vector>\n\n"
    "#include <lidarfx/lidarfx.hpp>\n${include_lines}\n\n${bodies}")
unmask_text("${source}" source)
# Written only when changed, so that an unchanged page does not rebuild the test.
if(EXISTS "${OUTPUT}")
    file(READ "${OUTPUT}" old)
endif()
if(NOT old STREQUAL source)
    file(WRITE "${OUTPUT}" "${source}")
endif()
if(STAMP)
    file(TOUCH "${STAMP}")
endif()
message(STATUS "docs snippets: ${snippet_count} code blocks and ${table_count} options tables from ${DOCS}")
