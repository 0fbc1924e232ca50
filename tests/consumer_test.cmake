# The installed package as a user meets it: `cmake --install` into a temporary prefix, the
# example consumer configured, built and run against it, and the installed boxpile running its
# main job and an installed sweep grid from an unrelated directory (it finds its default scene and
# the grids in P/share/boxpile).
# Arguments: -DBUILD=<boxpile build dir> -DSOURCE=<examples/consumer> -DWORK=<scratch dir>.

file(REMOVE_RECURSE ${WORK})
set(prefix ${WORK}/prefix)

function(run_step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err
                  WORKING_DIRECTORY ${WORK})
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${out}\n${err}")
  endif()
  set(step_output "${out}" PARENT_SCOPE)
endfunction()

file(MAKE_DIRECTORY ${WORK})
run_step("install" ${CMAKE_COMMAND} --install ${BUILD} --prefix ${prefix})
foreach(f include/boxpile/boxpile.hpp include/boxpile/sim/body.hpp include/boxpile/validation/conform/judge/judge.hpp
          lib/cmake/boxpile/boxpileConfig.cmake lib/cmake/boxpile/boxpileConfigVersion.cmake bin/boxpile
          share/boxpile/fixtures/scenes/bone_hits_pile.json share/boxpile/fixtures/contacts/touching.json
          share/boxpile/benchmarks/grids/accuracy_cost.json share/boxpile/benchmarks/grids/lab_report.json)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "not installed: ${f}")
  endif()
endforeach()

# The consumer reuses the compiler launcher of this build (ccache), so a rebuild is cheap.
set(launcher)
if(LAUNCHER)
  set(launcher -DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER})
endif()
run_step("configure the consumer" ${CMAKE_COMMAND} -S ${SOURCE} -B ${WORK}/consumer -DCMAKE_PREFIX_PATH=${prefix}
         -DCMAKE_BUILD_TYPE=Release ${launcher})
run_step("build the consumer" ${CMAKE_COMMAND} --build ${WORK}/consumer)
run_step("run the consumer" ${WORK}/consumer/consumer ${prefix}/share/boxpile/fixtures)
message(STATUS "${step_output}")

# The C++ example collider (our detector behind the line protocol) passes the installed judge.
run_step("conform the C++ example collider" ${prefix}/bin/boxpile conform --collider ${WORK}/consumer/own_collider
         --samples 300 --report ${WORK}/conform)

# The installed program's main job, from a directory that has nothing of boxpile in it.
file(MAKE_DIRECTORY ${WORK}/elsewhere)
execute_process(COMMAND ${prefix}/bin/boxpile WORKING_DIRECTORY ${WORK}/elsewhere RESULT_VARIABLE rc
                OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT EXISTS ${WORK}/elsewhere/boxpile-report/report.md)
  message(FATAL_ERROR "installed boxpile with no command failed (${rc}):\n${out}\n${err}")
endif()

# An installed sweep grid, by name, from the same directory: its scene paths (relative to the
# grid file) lead to the installed fixtures. Shard 1 of 1000 is the grid's first cell alone.
execute_process(COMMAND ${prefix}/bin/boxpile sweep accuracy_cost --shard 1/1000 --report sweep
                WORKING_DIRECTORY ${WORK}/elsewhere RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT EXISTS ${WORK}/elsewhere/sweep/sweep.json)
  message(FATAL_ERROR "installed boxpile sweep accuracy_cost failed (${rc}):\n${out}\n${err}")
endif()
