# Installs lidarfx into a scratch prefix and builds a separate project that uses find_package(lidarfx).
file(REMOVE_RECURSE "${WORK_DIR}")
set(build "${WORK_DIR}/lidarfx-build")
set(prefix "${WORK_DIR}/prefix")
function(run)
    execute_process(COMMAND ${ARGV} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
        message(FATAL_ERROR "command failed (${rc}): ${ARGV}\n${out}\n${err}")
    endif()
endfunction()
run(${CMAKE_COMMAND} -S "${SOURCE_DIR}" -B "${build}" -G "${GENERATOR}" -DCMAKE_CXX_COMPILER=${CXX}
    -DLIDARFX_BUILD_TESTS=OFF -DLIDARFX_BUILD_EXAMPLES=OFF -DLIDARFX_BUILD_BENCH=OFF
    -DCMAKE_INSTALL_PREFIX=${prefix})
run(${CMAKE_COMMAND} --install "${build}")
run(${CMAKE_COMMAND} -S "${SOURCE_DIR}/tests/consumer" -B "${WORK_DIR}/consumer-build" -G "${GENERATOR}"
    -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_PREFIX_PATH=${prefix})
run(${CMAKE_COMMAND} --build "${WORK_DIR}/consumer-build")
run("${WORK_DIR}/consumer-build/consumer")
run("${WORK_DIR}/consumer-build/consumer_synth")
message(STATUS "consumer project built and ran against the installed lidarfx")
