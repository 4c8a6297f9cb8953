# The library's headers follow .clang-format (Debian's clang-format 14): clang-format would change no line.
# Tables kept as transcribed are fenced by `// clang-format off` / `on`.
find_program(CLANG_FORMAT NAMES clang-format clang-format-14 REQUIRED)
file(GLOB_RECURSE headers "${SOURCE_DIR}/include/lidarfx/*.hpp")
execute_process(COMMAND ${CLANG_FORMAT} --style=file --dry-run --Werror ${headers}
                WORKING_DIRECTORY "${SOURCE_DIR}" RESULT_VARIABLE rc ERROR_VARIABLE err)
list(LENGTH headers count)
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "headers that clang-format would change (run: clang-format -i on them):\n${err}")
endif()
message(STATUS "${count} headers follow .clang-format")
