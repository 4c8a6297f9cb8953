# SPDX-License-Identifier: Apache-2.0
# The program refuses what it cannot do well, at once, with a message naming the way out, and leaves no folder
# behind: each case is "exit code|phrase|another phrase|arguments separated by ^".
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
file(CREATE_LINK "${DATA}" "${WORK_DIR}/link.las" SYMBOLIC)
set(out "${WORK_DIR}/out")
set(cases
    "2|over the memory budget of 1 GiB|use --cell 0.1 or more|rasterize^${DATA}^--cell^0.001^--memory^1GiB^--out^${out}"
    "2|over 99 % of the cells would be empty|Use --cell 5 or more|rasterize^${DATA}^--cell^0.2^--out^${out}"
    "2|--threads must be >= 0|(got -1)|rasterize^${DATA}^--threads^-1^--out^${out}"
    "2|--memory expects|0.5x|rasterize^${DATA}^--memory^0.5x^--out^${out}"
    "2|--crop expects|min < max|rasterize^${DATA}^--crop^1,2,0,4^--out^${out}"
    "1|is the same file as|give each file once|rasterize^${DATA}^${WORK_DIR}/link.las^--out^${out}"
    "1|option --cell is given more than once|--cell|rasterize^${DATA}^--cell^2^--cell^3^--out^${out}"
    "1|unknown option -v|options are --name|rasterize^-v^${DATA}^--out^${out}"
    "1|cannot open|no-such.las|rasterize^--out^${out}^--^${WORK_DIR}/no-such.las"
    "2|--veg-height must be a finite number > 0|(got -1)|water^${DATA}^--veg-height^-1^--out^${out}"
    "2|--theta-max must be in [--theta-start, 90] degrees|(got 1)|water^${DATA}^--theta-start^5^--theta-max^1^--out^${out}"
    "2|--alpha must be in (0, 1)|(got 2)|water^${DATA}^--alpha^2^--out^${out}"
    "2|--island-min-area must be >= 0|(got nan)|water^${DATA}^--island-min-area^nan^--out^${out}"
    "2|--formats takes a comma-separated list|tiff|rasterize^${DATA}^--formats^tiff^--out^${out}"
    "2|--hull-radius must be a finite number >= 0|(got -5)|water^${DATA}^--hull-radius^-5^--out^${out}"
    "1|exists and is not a folder|${DATA}|demo^--size^100^--out^${DATA}")
include("${CMAKE_CURRENT_LIST_DIR}/expect_refusals.cmake")
