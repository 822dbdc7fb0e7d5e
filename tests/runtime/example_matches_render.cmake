# The host example's effects against `motionfx render` of the same scene (example_scene.json: the
# hero scene's kick lines and smoke, without its toon outline, bloom and tone map, so that both
# pictures are linear colour clamped to 8-bit sRGB), camera, size and frame: the example is run as
# it draws and with its colours black, the program with --layers, and motionfx_example_check
# compares the example's effects layer laid over the program's picture with the program's frame.
foreach(var EXAMPLE MOTIONFX CHECK SOURCE_DIR WORK_DIR)
    if(NOT DEFINED ${var})
        message(FATAL_ERROR "example_matches_render.cmake needs -D${var}=...")
    endif()
endforeach()
set(scene ${SOURCE_DIR}/tests/runtime/example_scene.json)
set(frame 20)
set(size 320x180)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR}/host ${WORK_DIR}/black)

function(run what)
    execute_process(COMMAND ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
    message(STATUS "${what}:\n${out}${err}")
    if(NOT code EQUAL 0)
        message(FATAL_ERROR "${what} failed (${code})")
    endif()
endfunction()

math(EXPR frames "${frame} + 1")
run("the example" ${EXAMPLE} --scene ${scene} --frames ${frames} --size ${size} --save ${frame}
    --out ${WORK_DIR}/host)
run("the example, black" ${EXAMPLE} --scene ${scene} --frames ${frames} --size ${size}
    --save ${frame} --out ${WORK_DIR}/black --black)
run("motionfx render" ${MOTIONFX} render ${scene} --frames ${frames} --size ${size} --layers
    --out ${WORK_DIR}/program)
string(LENGTH "${frame}" digits)
math(EXPR pad "4 - ${digits}")
string(REPEAT "0" ${pad} zeros)
set(n ${zeros}${frame})
run("the comparison" ${CHECK} ${WORK_DIR}/host/frame_${n}.ppm ${WORK_DIR}/host/under_${n}.ppm
    ${WORK_DIR}/black/frame_${n}.ppm ${WORK_DIR}/program/frame_${n}.png
    ${WORK_DIR}/program/character_${n}.png)
