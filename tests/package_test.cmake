# `cpack -G DEB` makes a package that unpacks and runs: built into a scratch folder, unpacked with
# dpkg -x (nothing installed on this machine), and its boxpile run on an installed fixture.
# Arguments: -DBUILD=<boxpile build dir> -DWORK=<scratch dir>.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})

function(run_step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err WORKING_DIRECTORY ${WORK})
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${out}\n${err}")
  endif()
  set(step_output "${out}" PARENT_SCOPE)
endfunction()

run_step("cpack" ${CMAKE_COMMAND} -E chdir ${BUILD} cpack -G DEB -B ${WORK}/package)
file(GLOB deb ${WORK}/package/boxpile_*.deb)
if(NOT deb)
  message(FATAL_ERROR "cpack made no .deb in ${WORK}/package")
endif()
run_step("dpkg-deb -I" dpkg-deb -I ${deb})
foreach(dependency libode-dev libbullet-dev libeigen3-dev nlohmann-json3-dev)
  string(FIND "${step_output}" "${dependency}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "the package does not depend on ${dependency}:\n${step_output}")
  endif()
endforeach()
run_step("dpkg -x" dpkg -x ${deb} ${WORK}/root)
foreach(f usr/bin/boxpile usr/include/boxpile/boxpile.hpp usr/share/boxpile/fixtures/contacts/touching.json)
  if(NOT EXISTS ${WORK}/root/${f})
    message(FATAL_ERROR "not in the package: ${f}")
  endif()
endforeach()
file(GLOB_RECURSE config ${WORK}/root/usr/*/boxpileConfig.cmake)
if(NOT config)
  message(FATAL_ERROR "no boxpileConfig.cmake in the package")
endif()
# The unpacked program finds its data in the unpacked usr/share/boxpile.
run_step("the packaged boxpile" ${WORK}/root/usr/bin/boxpile contacts
         ${WORK}/root/usr/share/boxpile/fixtures/contacts/touching.json --format json --engines own)
string(JSON n LENGTH "${step_output}" engines own contacts)
if(NOT n EQUAL 4)
  message(FATAL_ERROR "the packaged boxpile: ${n} contacts for touching.json, expected 4:\n${step_output}")
endif()
run_step("the packaged conform" ${WORK}/root/usr/bin/boxpile conform
         --collider "${WORK}/root/usr/bin/boxpile contacts --serve" --samples 50 --report ${WORK}/conform)
# The node-hosted engines run from the unpacked tree when the package holds their npm packages
# (a build tree without reference/node_modules packages boxpile without them): their adapters,
# the protocol loop they share and the packages must all be installed. free_fall's box starts at
# z 10 m rising at 2 m/s: after 0.1 s, z = 10 + 0.2 - g 0.1^2 / 2 = 10.1510 m; each engine's
# integrator lags by at most g t dt / 2 = 2.0e-3 m at dt 1/240 s, so 3e-3 m is the gate.
if(EXISTS ${WORK}/root/usr/share/boxpile/reference/node_modules)
  foreach(engine jolt rapier mujoco-wasm)
    run_step("the packaged boxpile with ${engine}" ${WORK}/root/usr/bin/boxpile run
             ${WORK}/root/usr/share/boxpile/fixtures/scenes/free_fall.json --engine ${engine} --duration 0.1)
    string(REGEX MATCH "position \\([^,]+, [^,]+, ([0-9.]+)\\)" found "${step_output}")
    if(NOT found OR CMAKE_MATCH_1 LESS 10.148 OR CMAKE_MATCH_1 GREATER 10.154)
      message(FATAL_ERROR "the packaged boxpile with ${engine}: expected the box at z 10.151 +- 0.003 m:\n${step_output}")
    endif()
  endforeach()
endif()
