# SPDX-License-Identifier: Apache-2.0
# write_block_dsm(path n r0 r1 c0 c1 top): an n x n ESRI ASCII DSM of 1 m cells at (1000, 2000), flat ground at
# 100 m and one block at `top` m on rows [r0, r1) and columns [c0, c1).
function(write_block_dsm path n r0 r1 c0 c1 top)
    set(text "ncols ${n}\nnrows ${n}\nxllcorner 1000\nyllcorner 2000\ncellsize 1\nNODATA_value -9999\n")
    math(EXPR last "${n} - 1")
    foreach(r RANGE ${last})
        set(row "")
        foreach(c RANGE ${last})
            if(r GREATER_EQUAL ${r0} AND r LESS ${r1} AND c GREATER_EQUAL ${c0} AND c LESS ${c1})
                string(APPEND row " ${top}")
            else()
                string(APPEND row " 100")
            endif()
        endforeach()
        string(APPEND text "${row}\n")
    endforeach()
    file(WRITE "${path}" "${text}")
endfunction()
