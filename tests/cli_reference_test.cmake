# `boxpile contacts` with the reference engines and `boxpile run`, driven as a user would:
# exit codes, messages and the JSON they print or write.
# Run with -DBOXPILE=<the boxpile executable> -DFIXTURES=<fixtures dir> -DWORK=<scratch dir>.

file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
include("${CMAKE_CURRENT_LIST_DIR}/cli_helpers.cmake")

# --- contacts: all three engines with diffs ---
run_boxpile(0 contacts "${FIXTURES}/contacts/yaw45_octagon.json")
expect_length("${out}" 8 engines own contacts)
expect_length("${out}" 8 engines ode contacts)
expect_length("${out}" 4 engines bullet contacts)  # Bullet caps box-box at 4
expect_length("${out}" 8 engines mujoco contacts)
expect_length("${out}" 4 engines dart contacts)  # so do DART's and FCL's
expect_length("${out}" 4 engines fcl contacts)
expect_json("${out}" 4 diff bullet points bullet)
expect_match("${out}" "^0(\\.0)?$" diff ode normal_angle)
expect_json("${out}" ON diff bullet smaller_inside_hull)
expect_json("${out}" box-box kind)

run_boxpile(0 contacts "${FIXTURES}/contacts/plane_flat.json")
expect_length("${out}" 7 engines)  # own, ode, bullet, bullet-multipoint, mujoco, dart and fcl
expect_length("${out}" 4 engines mujoco contacts)
expect_length("${out}" 1 engines bullet contacts)
expect_json("${out}" box-plane kind)

run_boxpile(0 contacts "${FIXTURES}/contacts/aligned_offset.json" --engines ode,own)
expect_length("${out}" 2 engines)
expect_length("${out}" 1 diff)
expect_json("${out}" 4 diff ode points ode)

run_boxpile(0 contacts "${FIXTURES}/contacts/aligned_offset.json" --engines bullet)
string(JSON diff ERROR_VARIABLE no_diff GET "${out}" diff)
if(NOT no_diff)
  fail("contacts --engines bullet: a diff without own")
endif()

run_boxpile(2 contacts "${FIXTURES}/contacts/aligned_offset.json" --engines own,physx)
expect_contains("${err}" "physx")

# --- run ---
run_boxpile(0 run "${FIXTURES}/scenes/stack_5.json" --engine ode --duration 0.5)
expect_contains("${out}" "engine ode")
expect_contains("${out}" "120 steps")

run_boxpile(0 run "${FIXTURES}/scenes/stack_5.json" --engine bullet --duration 0.5 --every 10
            --out "${WORK}/run.json")
# It says what it wrote where, and prints no summary.
expect_contains("${out}" "bullet on stack_5, 120 steps, 13 frames recorded\nrun: ${WORK}/run.json")
file(READ "${WORK}/run.json" run)
expect_json("${run}" bullet engine)
expect_json("${run}" stack_5 scene)
expect_json("${run}" 120 steps)
expect_length("${run}" 13 frames)  # steps 0, 10, ..., 120
expect_length("${run}" 5 final bodies)
expect_json("${run}" b4 final bodies 4 name)
expect_length("${run}" 4 frames 0 bodies 0 orientation)
# The start, which no step led to, holds the first step's contact set: the stack's resting pairs.
string(JSON start_count GET "${run}" frames 0 contact_count)
if(start_count LESS 5)
  fail("run --out: ${start_count} contacts at the start, expected the first step's (at least one per resting pair)")
endif()
expect_length("${run}" ${start_count} frames 0 contacts)
expect_length("${run}" 5 shapes bodies)
expect_match("${run}" "^0(\\.0)?$" shapes ground offset)
expect_length("${run}" 1 shapes bodies 0 boxes)
# A resting stack: every frame after the start holds the contacts of its five resting pairs.
string(JSON count GET "${run}" frames 12 contact_count)
expect_length("${run}" ${count} frames 12 contacts)
if(count LESS 5)
  fail("run --out: ${count} contacts at the end of a resting stack of five, expected at least 5")
endif()
# Boxes stacked straight up touch face to face: every normal is vertical.
string(JSON normal_z GET "${run}" frames 12 contacts 0 normal 2)
string(REGEX REPLACE "^-" "" normal_z "${normal_z}")
if(NOT normal_z GREATER 0.999999)
  fail("run --out: contact 0 has normal z ${normal_z}, expected +-1 (vertical)")
endif()
expect_match("${run}" "^(0\\.50*[0-9]?|0\\.49999999999999[0-9]*)$" final t)

run_boxpile(0 run "${FIXTURES}/scenes/stack_5.json" --engine ode --dt 0.01 --duration 0.1 --out "${WORK}/dt.json")
file(READ "${WORK}/dt.json" run)
expect_json("${run}" 10 steps)
expect_match("${run}" "^0\\.01$" dt)

run_boxpile(0 run "${FIXTURES}/scenes/stack_5.json" --engine own --duration 0.5 --every 60 --out "${WORK}/own.json")
file(READ "${WORK}/own.json" run)
expect_json("${run}" 120 steps)
expect_json("${run}" own engine)
string(JSON energy GET "${run}" frames 1 energy total)
string(JSON pen GET "${run}" frames 1 max_penetration)
string(JSON passes GET "${run}" frames 1 solver collision_passes)
if(pen GREATER 1e-6)
  message(SEND_ERROR "own run: penetration ${pen} m in a resting stack")
endif()
# Potential energy of 5 unit boxes at z = 0.5 .. 4.5 under g = 9.81: 9.81 * 12.5 = 122.625 J.
if(energy LESS 122.62 OR energy GREATER 122.63)
  message(SEND_ERROR "own run: total energy ${energy} J, expected 122.625 J")
endif()
run_boxpile(0 run "${FIXTURES}/scenes/stack_5.json" --engine ode --duration 0.1 --out "${WORK}/ode_metrics.json")
file(READ "${WORK}/ode_metrics.json" run)
string(JSON energy GET "${run}" frames 0 energy total)
if(energy LESS 122.62 OR energy GREATER 122.63)
  message(SEND_ERROR "ode run: total energy ${energy} J at the start, expected 122.625 J")
endif()
run_boxpile(2 run "${FIXTURES}/scenes/stack_5.json" --engine physx)
expect_contains("${err}" "unknown engine \"physx\"; available: own, own-impulse, own-penalty, ode, bullet, mujoco, dart")
run_boxpile(2 run "${FIXTURES}/bad/overlap.json" --engine ode)
expect_contains("${err}" "overlap.json")
run_boxpile(2 run "${WORK}/missing.json" --engine ode)
expect_contains("${err}" "missing.json")
run_boxpile(2 run "${FIXTURES}/scenes/stack_5.json" --engine ode --dt -1)
# A missing parent directory is created; the file appears whole.
run_boxpile(0 run "${FIXTURES}/scenes/stack_5.json" --engine ode --duration 0.1 --out "${WORK}/no/such/dir/x.json")
if(NOT EXISTS "${WORK}/no/such/dir/x.json")
  fail("x.json not written under new parent directories")
endif()

# --- view: a replay page for a run file ---
run_boxpile(0 view "${WORK}/run.json")
expect_contains("${out}" "run.html")
file(READ "${WORK}/run.html" page)
expect_contains("${page}" "\"format\":\"boxpile-replay-1\"")
expect_contains("${page}" "OrbitControls")
run_boxpile(0 view "${WORK}/run.json" --out "${WORK}/elsewhere.html")
expect_exists("${WORK}/elsewhere.html")
# Bad input: exit 2, the file and field named, nothing written.
run_boxpile(2 view "${WORK}/missing.json")
expect_contains("${err}" "missing.json")
expect_refused("stack_5.json" "${WORK}/scene.html" view "${FIXTURES}/scenes/stack_5.json" --out "${WORK}/scene.html")
file(WRITE "${WORK}/broken.json" "{\"scene\": \"x\", \"engine\": \"own\", \"dt\": 0.01, \"shapes\": {\"ground\": null, \"bodies\": []}, \"frames\": []}")
expect_refused("broken.json: frames: a recording needs at least one frame" "${WORK}/broken.html" view "${WORK}/broken.json")
# A missing parent directory is created, as for every output.
run_boxpile(0 view "${WORK}/run.json" --out "${WORK}/no/such/view/page.html")
expect_exists("${WORK}/no/such/view/page.html")
run_boxpile(2 view "${WORK}/run.json" --out "${WORK}/run.json")
expect_contains("${err}" "replace its own input")
