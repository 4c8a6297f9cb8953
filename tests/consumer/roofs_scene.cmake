# SPDX-License-Identifier: Apache-2.0
# write_roofs_scene(dir): dir/dsm.asc and dir/dtm.asc (no CRS) on 50 x 50 cells of 1 m at (1000, 2000), ground at
# 100 m: a shed roof on rows [10, 22) and columns [10, 30) rising 0.5 m per cell to the north from 106 m (tilt
# atan(0.5) = 26.57 deg, facing south), and a flat roof at 108 m on rows [30, 42) and columns [10, 25).
# Row r spans y 2050 - r - 1 .. 2050 - r.
function(write_roofs_scene dir)
    set(header "ncols 50\nnrows 50\nxllcorner 1000\nyllcorner 2000\ncellsize 1\nNODATA_value -9999\n")
    set(dsm "${header}")
    set(dtm "${header}")
    foreach(r RANGE 49)
        set(row "")
        set(ground "")
        foreach(c RANGE 49)
            if(r GREATER_EQUAL 10 AND r LESS 22 AND c GREATER_EQUAL 10 AND c LESS 30)
                math(EXPR half "21 - ${r}")  # rows north of the eave rise 0.5 m per 1 m cell
                math(EXPR whole "${half} / 2")
                math(EXPR frac "${half} % 2 * 5")
                math(EXPR whole "106 + ${whole}")
                string(APPEND row " ${whole}.${frac}")
            elseif(r GREATER_EQUAL 30 AND r LESS 42 AND c GREATER_EQUAL 10 AND c LESS 25)
                string(APPEND row " 108")
            else()
                string(APPEND row " 100")
            endif()
            string(APPEND ground " 100")
        endforeach()
        string(APPEND dsm "${row}\n")
        string(APPEND dtm "${ground}\n")
    endforeach()
    file(WRITE "${dir}/dsm.asc" "${dsm}")
    file(WRITE "${dir}/dtm.asc" "${dtm}")
endfunction()
