# Included by the tiled-water test scripts: empties WORK_DIR and writes the synthetic survey of LAS files
# (make_water_survey: lakes and a river across file and tile borders) into ${WORK_DIR}/survey.
file(REMOVE_RECURSE "${WORK_DIR}")
execute_process(COMMAND "${MAKE_SURVEY}" "${WORK_DIR}/survey" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "make_water_survey failed (${rc}):\n${out}\n${err}")
endif()
