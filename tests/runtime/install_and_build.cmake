# Installs the build tree BUILD_DIR into a scratch prefix under WORK_DIR, checks that the prefix
# holds the public header alone, then configures, builds and runs examples/host (SOURCE_DIR)
# against that prefix with nothing else on CMake's search path. Fails on the first step that does.
foreach(var BUILD_DIR SOURCE_DIR WORK_DIR)
    if(NOT DEFINED ${var})
        message(FATAL_ERROR "install_and_build.cmake needs -D${var}=...")
    endif()
endforeach()
set(prefix ${WORK_DIR}/prefix)
set(example_build ${WORK_DIR}/example-build)
file(REMOVE_RECURSE ${WORK_DIR})

function(run what)
    execute_process(COMMAND ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(NOT code EQUAL 0)
        message(FATAL_ERROR "${what} failed (${code}):\n${out}\n${err}")
    endif()
    set(last_output "${out}" PARENT_SCOPE)
endfunction()

run("cmake --install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})

# Only the public header is installed.
file(GLOB_RECURSE headers RELATIVE ${prefix} ${prefix}/*.h ${prefix}/*.hpp)
if(NOT headers STREQUAL "include/motionfx/motionfx.h")
    message(FATAL_ERROR "the prefix should hold include/motionfx/motionfx.h alone; it holds: ${headers}")
endif()
foreach(file lib/cmake/motionfx/motionfxConfig.cmake lib/cmake/motionfx/motionfxConfigVersion.cmake)
    if(NOT EXISTS ${prefix}/${file})
        message(FATAL_ERROR "the prefix lacks ${file}")
    endif()
endforeach()

# The example knows the prefix alone: no package registry, no other prefix.
run("configuring examples/host" ${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples/host -B ${example_build}
    -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF
    -DCMAKE_FIND_USE_SYSTEM_PACKAGE_REGISTRY=OFF -DCMAKE_BUILD_TYPE=Release)
run("building examples/host" ${CMAKE_COMMAND} --build ${example_build} -j 2)
# Two small frames: the frames themselves are the RuntimeExample tests' (tests/CMakeLists.txt).
run("running examples/host" ${example_build}/motionfx_host --headless --frames 2 --size 160x90
    --scene ${SOURCE_DIR}/docs/scenes/hero.json)
message(STATUS "${last_output}")
if(NOT last_output MATCHES "motionfx 0\\.[0-9]+\\.[0-9]+ runtime on ")
    message(FATAL_ERROR "examples/host did not report its runtime:\n${last_output}")
endif()
if(NOT last_output MATCHES "hero.json: [1-9][0-9]* effects, 1 smoke grids")
    message(FATAL_ERROR "examples/host did not make the hero scene's effects:\n${last_output}")
endif()
