# Drives the boxpile executable as a user would and checks exit codes, messages and output.
# Run by ctest as: cmake -DBOXPILE=... -DFIXTURES=... -DWORK=... -P cli_test.cmake
cmake_minimum_required(VERSION 3.25)

file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")

# run(<name> <expected exit> <must-contain or ""> args...): runs boxpile, checks the exit code
# and that stdout+stderr contains the text.
function(run name expected_rc must_contain)
  execute_process(COMMAND "${BOXPILE}" ${ARGN}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  set(all "${out}${err}")
  if(NOT rc EQUAL expected_rc)
    message(SEND_ERROR "${name}: exit ${rc}, expected ${expected_rc}\n${all}")
  elseif(NOT must_contain STREQUAL "")
    string(FIND "${all}" "${must_contain}" at)
    if(at EQUAL -1)
      message(SEND_ERROR "${name}: output lacks \"${must_contain}\"\n${all}")
    endif()
  endif()
  set(last_out "${out}" PARENT_SCOPE)
endfunction()

run(version 0 "boxpile 0." --version)
run(help 0 "contacts" --help)
# No command: the main job, compare on the bone scene into ./boxpile-report/.
execute_process(COMMAND "${BOXPILE}" WORKING_DIRECTORY "${WORK}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(SEND_ERROR "no_command: exit ${rc}, expected 0\n${out}${err}")
endif()
string(FIND "${out}" "boxpile-report/report.md" at)
if(at EQUAL -1)
  message(SEND_ERROR "no_command: the report's place is not printed\n${out}")
endif()
foreach(f report.json report.md energy.svg position_difference.svg)
  if(NOT EXISTS "${WORK}/boxpile-report/${f}")
    message(SEND_ERROR "no_command: boxpile-report/${f} missing")
  endif()
endforeach()
run(unknown_flag 2 "--frobnicate" contacts --frobnicate x.json)

# The octagon: a unit box yawed 45 degrees resting 1 cm deep on another.
file(WRITE "${WORK}/octagon.json" [=[
{"a": {"half_extents": [0.5, 0.5, 0.5], "position": [0, 0, 0.99],
       "orientation": [0.9238795325112867, 0, 0, 0.3826834323650898]},
 "b": {"half_extents": [0.5, 0.5, 0.5], "position": [0, 0, 0], "orientation": [1, 0, 0, 0]}}
]=])
run(octagon 0 "" contacts "${WORK}/octagon.json" --engines own)
string(JSON n LENGTH "${last_out}" engines own contacts)
if(NOT n EQUAL 8)
  message(SEND_ERROR "octagon: ${n} contacts, expected 8\n${last_out}")
endif()
string(JSON depth GET "${last_out}" engines own contacts 0 depth)
if(depth LESS 0.0099 OR depth GREATER 0.0101)
  message(SEND_ERROR "octagon: depth ${depth}, expected 0.01")
endif()
run(octagon_reduced 0 "" contacts "${WORK}/octagon.json" --engines own --reduce)
string(JSON n LENGTH "${last_out}" engines own contacts)
if(NOT n EQUAL 4)
  message(SEND_ERROR "octagon --reduce: ${n} contacts, expected 4")
endif()

# A box on the ground plane: four corners.
file(WRITE "${WORK}/plane.json" [=[
{"a": {"half_extents": [0.5, 0.5, 0.5], "position": [0, 0, 0.49]},
 "b": {"plane": {"normal": [0, 0, 1], "offset": 0}}}
]=])
run(plane 0 "" contacts "${WORK}/plane.json" --engines own)
string(JSON n LENGTH "${last_out}" engines own contacts)
if(NOT n EQUAL 4)
  message(SEND_ERROR "plane: ${n} contacts, expected 4")
endif()

# Bad queries: exit 2, the file and the JSON path named.
file(WRITE "${WORK}/bad_extent.json" [=[
{"a": {"half_extents": [0.5, -1, 0.5], "position": [0, 0, 0]},
 "b": {"plane": {"normal": [0, 0, 1], "offset": 0}}}
]=])
run(bad_extent 2 "bad_extent.json: a.half_extents[1]" contacts "${WORK}/bad_extent.json")
file(WRITE "${WORK}/bad_syntax.json" "{\"a\": {\"half_extents\": [0.5, 0.5 0.5]}}\n")
run(bad_syntax 2 "line 1" contacts "${WORK}/bad_syntax.json")
run(missing_file 2 "no_such_query.json" contacts "${WORK}/no_such_query.json")

# The contact methods: a key of one method under the other, an unknown method, static friction
# under the impulse method and a dt past the penalty method's stability bound: exit 2 naming the key.
function(scene_with name solver material dt)
  file(WRITE "${WORK}/${name}.json" "{\"name\": \"${name}\", \"ground\": {}, \"material\": ${material},
 \"bodies\": [{\"name\": \"b\", \"mass\": 1, \"half_extents\": [0.5, 0.5, 0.5], \"position\": [0, 0, 0.5]}],
 \"solver\": ${solver}, \"time\": {\"dt\": ${dt}, \"duration\": 0.1}}\n")
endfunction()
scene_with(penalty_key_under_impulse "{\"method\": \"impulse\", \"stiffness\": 1000}" "{}" 0.004)
run(penalty_key_under_impulse 2 "penalty_key_under_impulse.json: solver.stiffness: belongs to the penalty method"
    run "${WORK}/penalty_key_under_impulse.json" --engine own)
scene_with(impulse_key_under_penalty "{\"method\": \"penalty\", \"contact_passes\": 10}" "{}" 0.004)
run(impulse_key_under_penalty 2 "impulse_key_under_penalty.json: solver.contact_passes: belongs to the impulse method"
    run "${WORK}/impulse_key_under_penalty.json" --engine own)
scene_with(unknown_method "{\"method\": \"springs\"}" "{}" 0.004)
run(unknown_method 2 "unknown_method.json: solver.method" run "${WORK}/unknown_method.json" --engine own)
scene_with(static_under_impulse "{}" "{\"friction\": 0.2, \"static_friction\": 0.5}" 0.004)
run(static_under_impulse 2 "static_under_impulse.json: material.static_friction: belongs to the penalty method"
    run "${WORK}/static_under_impulse.json" --engine own)
# k = 1e9 N/m on a 1 kg box: the bound is 2 (sqrt(2) - 1) / sqrt(4e9) = 1.3e-5 s, dt 0.1 s would
# need 96 000 derived substeps (0.08 of the bound each).
scene_with(past_bound "{\"method\": \"penalty\", \"stiffness\": 1e9}" "{}" 0.1)
run(past_bound 2 "past_bound.json: time.dt: dt 0.1 s breaks the penalty method's stability bound"
    run "${WORK}/past_bound.json" --engine own)
# The same with its own substeps is taken as it is.
scene_with(past_bound_substeps "{\"method\": \"penalty\", \"stiffness\": 1e9, \"substeps\": 2}" "{}" 0.1)
run(past_bound_substeps 0 "" run "${WORK}/past_bound_substeps.json" --engine own --duration 0)
# --profile prints each stage's time per step for ours, and refuses an engine that keeps none.
run(profile 0 "contact_loop" run "${FIXTURES}/scenes/stack_5.json" --engine own --duration 0.1 --profile)
run(profile_other_engine 2 "--profile: engine ode keeps no per-stage profile" run "${FIXTURES}/scenes/stack_5.json"
    --engine ode --duration 0.1 --profile)
# own-penalty forces the method on an impulse scene, and says so in its frames.
run(own_penalty 0 "" run "${FIXTURES}/scenes/stack_5.json" --engine own-penalty --duration 0.1 --out "${WORK}/penalty.json")
file(READ "${WORK}/penalty.json" penalty_run)
string(JSON method GET "${penalty_run}" frames 1 solver method)
string(JSON engine GET "${penalty_run}" engine)
if(NOT method STREQUAL "penalty" OR NOT engine STREQUAL "own-penalty")
  message(SEND_ERROR "own-penalty: method ${method}, engine ${engine}")
endif()

# --- the command line as a new user types it ---
# A list option takes one word: the file after it stays the scene or the query.
run(engines_then_scene 0 "report.md" compare --engines own,ode "${FIXTURES}/scenes/stack_5.json" --duration 0.02
    --report "${WORK}/engines_then_scene")
run(engines_then_query 0 "" contacts --engines own,ode "${FIXTURES}/contacts/aligned_offset.json" --format json)
string(JSON n LENGTH "${last_out}" engines ode contacts)
if(NOT n EQUAL 4)
  message(SEND_ERROR "contacts --engines own,ode QUERY: ${n} ode contacts, expected 4\n${last_out}")
endif()
# --out names every command's output; --report is the same on the commands that write a report.
run(compare_out 0 "${WORK}/compare_out/report.md" compare "${FIXTURES}/scenes/stack_5.json" --engines own --duration 0.02
    --out "${WORK}/compare_out")
# Names use hyphens; the old underscore spelling is refused with the new name.
run(old_detector_name 2 "did you mean \"bullet-multipoint\"" contacts --engines bullet_multipoint
    "${FIXTURES}/contacts/plane_flat.json")
run(new_detector_name 0 "" contacts --engines bullet-multipoint "${FIXTURES}/contacts/plane_flat.json" --format json)
# Each command's help gives its own exit codes, not the top level's text.
foreach(pair "conform;0 the collider is within every gate" "stability;1 our engine failed a check"
             "run;1 a state became non-finite" "sweep;are findings in it")
  list(GET pair 0 command)
  list(GET pair 1 text)
  run(help_${command} 0 "${text}" ${command} --help)
  string(FIND "${last_out}" "Without a command" at)
  if(NOT at EQUAL -1)
    message(SEND_ERROR "${command} --help repeats the top level's text\n${last_out}")
  endif()
endforeach()
run(help_top 0 "Without a command" --help)
# run --out says what it wrote where.
run(run_out_says 0 "run: ${WORK}/said.json" run "${FIXTURES}/scenes/stack_5.json" --engine own --duration 0.02
    --out "${WORK}/said.json")
string(FIND "${last_out}" "2 frames recorded" at)
if(at EQUAL -1)
  message(SEND_ERROR "run --out: the frames recorded are not said\n${last_out}")
endif()

# --- boxpile scene: a valid scene on stdout or into --out, that loads and runs ---
run(scene_pyramid 0 "" scene pyramid --base 10)
file(WRITE "${WORK}/pyramid.json" "${last_out}")
string(JSON n LENGTH "${last_out}" bodies)
if(NOT n EQUAL 55)
  message(SEND_ERROR "scene pyramid --base 10: ${n} boxes, expected 55")
endif()
run(scene_pyramid_runs 0 "55 bodies" run "${WORK}/pyramid.json" --engine own --duration 0.05)
foreach(kind wall tower grid heap dominoes)
  run(scene_${kind} 0 "scene: ${WORK}/${kind}.json" scene ${kind} --out "${WORK}/${kind}.json")
  run(scene_${kind}_runs 0 "" run "${WORK}/${kind}.json" --engine ode --duration 0.05)
endforeach()
run(scene_size_not_taken 2 "--base: tower does not take it" scene tower --base 3)
run(scene_unknown_kind 2 "castle" scene castle)

# --- names from a scene cannot steer the terminal ---
# U+202E (a right-to-left override) in a body's name: escaped on a terminal (script(1) gives the
# run one), exact when piped and in the run file.
string(ASCII 226 128 174 rlo)  # its UTF-8 bytes E2 80 AE
file(WRITE "${WORK}/rlo.json" "{\"name\": \"rlo\", \"bodies\": [{\"name\": \"b${rlo}evil\", \"mass\": 1, \"half_extents\": [0.5, 0.5, 0.5], \"position\": [0, 0, 0.5]}],
 \"time\": {\"dt\": 0.01, \"duration\": 0.02}}")
find_program(SCRIPT_PROGRAM script)
if(SCRIPT_PROGRAM)
  execute_process(COMMAND "${SCRIPT_PROGRAM}" -qec "\"${BOXPILE}\" run \"${WORK}/rlo.json\" --engine own" /dev/null
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(FIND "${out}" "b\\u202eevil" escaped)
  string(FIND "${out}" "${rlo}" raw)
  if(NOT rc EQUAL 0 OR escaped EQUAL -1 OR NOT raw EQUAL -1)
    message(SEND_ERROR "a bidirectional override on a terminal: exit ${rc}, not escaped\n${out}${err}")
  endif()
else()
  message(SEND_ERROR "script(1) not found (util-linux)")
endif()
run(rlo_piped 0 "b${rlo}evil" run "${WORK}/rlo.json" --engine own)
run(rlo_file 0 "" run "${WORK}/rlo.json" --engine own --out "${WORK}/rlo_run.json")
file(READ "${WORK}/rlo_run.json" rlo_run)
string(FIND "${rlo_run}" "b${rlo}evil" at)
if(at EQUAL -1)
  message(SEND_ERROR "the run file does not hold the name exactly")
endif()
# A C1 control in a name is refused, echoed escaped; a name of zero-width spaces is refused.
string(ASCII 194 155 csi)  # U+009B
file(WRITE "${WORK}/csi.json" "{\"name\": \"csi\", \"bodies\": [{\"name\": \"b${csi}2J\", \"mass\": 1, \"half_extents\": [0.5, 0.5, 0.5], \"position\": [0, 0, 0.5]}],
 \"time\": {\"dt\": 0.01, \"duration\": 0.02}}")
run(csi_name 2 "csi.json: bodies[0].name: must not contain control characters, got \"b\\u009b2J\"" run "${WORK}/csi.json" --engine own)
execute_process(COMMAND "${BOXPILE}" run "${WORK}/csi.json" --engine own ERROR_VARIABLE err OUTPUT_QUIET)
string(FIND "${err}" "${csi}" raw)
if(NOT raw EQUAL -1)
  message(SEND_ERROR "a C1 control reached standard error raw\n${err}")
endif()
string(ASCII 226 128 139 zwsp)  # U+200B
file(WRITE "${WORK}/zwsp.json" "{\"name\": \"zwsp\", \"bodies\": [{\"name\": \"${zwsp}${zwsp}\", \"mass\": 1, \"half_extents\": [0.5, 0.5, 0.5], \"position\": [0, 0, 0.5]}],
 \"time\": {\"dt\": 0.01, \"duration\": 0.02}}")
run(zwsp_name 2 "zwsp.json: bodies[0].name: must not be only invisible characters" run "${WORK}/zwsp.json" --engine own)
