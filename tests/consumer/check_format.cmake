# Every C++ file of the project follows .clang-format (Debian's clang-format 14): the library's headers, the
# tests, the examples and the program, the benchmarks and the synthetic scenes; clang-format would change no
# line. Tables kept as transcribed are fenced by `// clang-format off` / `on`. The layering fixtures are
# exempt: their line numbers are part of what their self-tests check.
find_program(CLANG_FORMAT NAMES clang-format clang-format-14 REQUIRED)
set(files "")
foreach(dir include tests examples bench synth)
    file(GLOB_RECURSE found "${SOURCE_DIR}/${dir}/*.hpp" "${SOURCE_DIR}/${dir}/*.cpp")
    list(APPEND files ${found})
endforeach()
list(FILTER files EXCLUDE REGEX "/tests/layering/")
execute_process(COMMAND ${CLANG_FORMAT} --style=file --dry-run --Werror ${files}
                WORKING_DIRECTORY "${SOURCE_DIR}" RESULT_VARIABLE rc ERROR_VARIABLE err)
list(LENGTH files count)
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "files that clang-format would change (run: clang-format -i on them):\n${err}")
endif()
message(STATUS "${count} C++ files follow .clang-format")
