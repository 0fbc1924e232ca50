# `boxpile compare`, driven as a user would: the report it writes, its summary, and bad input
# (exit 2, a clear message, and no report directory, not even a half-written one).
# Run with -DBOXPILE=<the boxpile executable> -DFIXTURES=<fixtures dir> -DWORK=<scratch dir>.

file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
include("${CMAKE_CURRENT_LIST_DIR}/cli_helpers.cmake")


set(stack "${FIXTURES}/scenes/stack_5.json")

# --- a report ---
run_boxpile(0 compare "${stack}" --engines ode,bullet --duration 0.25 --report "${WORK}/report")
expect_contains("${out}" "us per step")
expect_contains("${out}" "ode vs bullet")
expect_contains("${out}" "report: ")
expect_contains("${out}" "report/report.md")
expect_contains("${err}" "[1/4] ode")
foreach(f report.json report.md energy.svg energy.dat energy.gp penetration.svg stack_height.svg
          position_difference.svg replay.html replay.json)
  if(NOT EXISTS "${WORK}/report/${f}")
    fail("compare: ${f} missing from the report")
  endif()
endforeach()
file(READ "${WORK}/report/report.json" report)
string(JSON n LENGTH "${report}" pairs)
if(NOT n EQUAL 1)
  fail("compare --engines ode,bullet: ${n} pairs, expected 1")
endif()
string(JSON ideal GET "${report}" engines ode stacks 0 ideal)
if(NOT ideal EQUAL 5)
  fail("compare: the stack of five's ideal height is ${ideal}, expected 5")
endif()
# stack_10 (unit cubes stacked touching): the ideal is the sum of the heights, 10 m, in report.json
# and in report.md's list of the stacks at the end (docs/tutorial.md, docs/compare.md).
run_boxpile(0 compare "${FIXTURES}/scenes/stack_10.json" --engines ode --duration 0.1 --report "${WORK}/report_10")
file(READ "${WORK}/report_10/report.json" report_10)
string(JSON ideal_10 GET "${report_10}" engines ode stacks 0 ideal)
string(JSON height_10 GET "${report_10}" engines ode stacks 0 height)
string(JSON bodies_10 LENGTH "${report_10}" engines ode stacks 0 bodies)
if(NOT ideal_10 EQUAL 10 OR NOT bodies_10 EQUAL 10)
  fail("compare stack_10: its stack of ${bodies_10} bodies has ideal ${ideal_10}, expected 10 bodies and 10 m")
endif()
# Settled within 1 mm of the ideal (ODE's resting cubes sink some 1e-4 m each into the next).
if(height_10 LESS 9.999 OR height_10 GREATER 10.001)
  fail("compare stack_10: ode's stack settles at ${height_10} m, expected within 1 mm of 10")
endif()
file(READ "${WORK}/report_10/report.md" md_10)
expect_contains("${md_10}" "- ode: 10 bodies, ")
expect_contains("${md_10}" " m (ideal 10.00000, error ")
# The replay's data: both engines, every recorded frame, the contact counts of report.json.
file(READ "${WORK}/report/replay.json" replay)
expect_json("${replay}" ode engines 0 name)
expect_json("${replay}" bullet engines 1 name)
string(JSON frames LENGTH "${report}" engines ode series t)
expect_length("${replay}" ${frames} engines 0 t)
string(JSON last_contacts GET "${report}" engines bullet series contacts 3)
expect_json("${replay}" ${last_contacts} engines 1 contact_counts 3)
if(last_contacts LESS 5)  # five boxes rest on each other and on the ground
  fail("compare: bullet's frame 3 holds ${last_contacts} contact points, expected at least 5")
endif()
# MuJoCo beside ODE in one compare: both run, and the report holds their pair.
run_boxpile(0 compare "${stack}" --engines ode,mujoco --duration 0.25 --report "${WORK}/report_mujoco")
expect_contains("${out}" "ode vs mujoco")
file(READ "${WORK}/report_mujoco/report.json" mujoco_report)
string(JSON mujoco_ideal GET "${mujoco_report}" engines mujoco stacks 0 ideal)
if(NOT mujoco_ideal EQUAL 5)
  fail("compare: mujoco's stack of five has ideal height ${mujoco_ideal}, expected 5")
endif()
string(JSON mujoco_contacts GET "${mujoco_report}" engines mujoco series contacts 3)
if(mujoco_contacts LESS 5)
  fail("compare: mujoco's frame 3 holds ${mujoco_contacts} contact points, expected at least 5")
endif()
# `boxpile view DIR` makes the page again, to another file; a directory that is not a report fails.
run_boxpile(0 view "${WORK}/report" --out "${WORK}/again.html")
expect_contains("${out}" "again.html")
file(SIZE "${WORK}/again.html" again)
file(SIZE "${WORK}/report/replay.html" first)
if(NOT again EQUAL first)
  fail("view DIR: ${again} bytes, compare wrote ${first}")
endif()
file(MAKE_DIRECTORY "${WORK}/not_a_report")
expect_refused("not a boxpile report directory" "${WORK}/not_a_report/replay.html" view "${WORK}/not_a_report")

# Without three.js the report is written all the same, without the page, and says so; `view`
# fails (exit 1: nothing wrong with the input) and writes nothing.
set(ENV{BOXPILE_THREE_DIR} "${WORK}/no_three")
run_boxpile(0 compare "${stack}" --engines bullet --duration 0.1 --report "${WORK}/no_three_report")
expect_contains("${err}" "libjs-three")
expect_exists("${WORK}/no_three_report/replay.json")
expect_absent("${WORK}/no_three_report/replay.html")
run_boxpile(1 view "${WORK}/no_three_report")
expect_contains("${err}" "three.min.js")
expect_absent("${WORK}/no_three_report/replay.html")
unset(ENV{BOXPILE_THREE_DIR})

# Run again into the same directory: the previous report is replaced whole.
run_boxpile(0 compare "${stack}" --engines bullet --duration 0.1 --report "${WORK}/report")
file(READ "${WORK}/report/report.json" report)
string(JSON n LENGTH "${report}" engines)
if(NOT n EQUAL 1)
  fail("compare into an existing report: ${n} engines, expected the new report's 1")
endif()

# --- bad input: exit 2, a message, nothing written ---
expect_refused("unknown engine \"physx\"; available: own, own-impulse, own-penalty, ode, bullet, mujoco, dart" "${WORK}/bad_engine"
               compare "${stack}" --engines own,physx --report "${WORK}/bad_engine")
expect_refused("missing.json" "${WORK}/bad_scene" compare "${WORK}/missing.json" --report "${WORK}/bad_scene")
expect_refused("overlap.json" "${WORK}/bad_overlap" compare "${FIXTURES}/bad/overlap.json" --report "${WORK}/bad_overlap")

file(WRITE "${WORK}/a_file" "not a directory\n")
run_boxpile(2 compare "${stack}" --duration 0.1 --report "${WORK}/a_file/report")
expect_contains("${err}" "report directory")
run_boxpile(2 compare "${stack}" --duration 0.1 --report "${WORK}/a_file")
expect_contains("${err}" "not a directory")

file(WRITE "${WORK}/mine/notes.txt" "keep me\n")
run_boxpile(2 compare "${stack}" --duration 0.1 --report "${WORK}/mine")
expect_contains("${err}" "not a boxpile report")
file(READ "${WORK}/mine/notes.txt" notes)
if(NOT notes STREQUAL "keep me\n")
  fail("compare touched a directory that is not a report")
endif()

run_boxpile(2 compare "${stack}" --dt 0 --report "${WORK}/bad_dt")
expect_absent("${WORK}/bad_dt")

# No staging directory is left behind by any of the runs above.
file(GLOB leftovers LIST_DIRECTORIES true "${WORK}/.*")
if(leftovers)
  fail("staging directories left behind: ${leftovers}")
endif()

# --- --starts: the outcome statistics over perturbed starts in report.json (docs/compare.md) ---
run_boxpile(0 compare "${stack}" --engines own,ode --duration 0.5 --starts 4 --report "${WORK}/starts")
expect_contains("${out}" "outcomes over 4 perturbed starts (0.001 m)")
expect_contains("${out}" "own vs ode: within chaos")
file(READ "${WORK}/starts/report.json" report)
expect_json("${report}" 4 outcomes starts)
expect_json("${report}" 0.001 outcomes perturbation)
expect_json("${report}" 1 outcomes seed)
expect_json("${report}" 0.01 outcomes significance)
expect_match("${report}" "^0\\.00416666" outcomes dt)
expect_length("${report}" 5 outcomes measures)
expect_length("${report}" 2 outcomes engines)
expect_json("${report}" own outcomes engines 0 label)
expect_json("${report}" ode outcomes engines 1 engine)
# The stack of five stands through 0.5 s from every start: five boxes, four of them stacked.
expect_length("${report}" 4 outcomes engines 0 samples tallest)
expect_json("${report}" 4 outcomes engines 1 summary stacked n)
expect_match("${report}" "^4(\\.0)?$" outcomes engines 1 summary stacked mean)
expect_match("${report}" "^0(\\.0)?$" outcomes engines 0 non_finite)
expect_json("${report}" own outcomes pairs 0 a)
expect_json("${report}" ode outcomes pairs 0 b)
expect_json("${report}" "within chaos" outcomes pairs 0 verdict)
expect_length("${report}" 5 outcomes pairs 0 tests)
foreach(key measure ks_statistic ks_p ks_exact welch_t welch_df welch_p differ)
  string(JSON value ERROR_VARIABLE error GET "${report}" outcomes pairs 0 tests 0 ${key})
  if(error)
    fail("compare --starts: outcomes.pairs[0].tests[0] has no ${key}")
  endif()
endforeach()
# --starts 0 (the default): no outcome statistics.
run_boxpile(0 compare "${stack}" --engines own --duration 0.1 --starts 0 --report "${WORK}/no_starts")
file(READ "${WORK}/no_starts/report.json" report)
string(JSON type TYPE "${report}" outcomes)
if(NOT type STREQUAL "NULL")
  fail("compare --starts 0: outcomes is ${type}, expected null")
endif()
# Bad values: exit 2 naming the flag, nothing written.
expect_refused("--starts: must be in [0, 500], got -1" "${WORK}/bad" compare "${stack}" --engines own --starts -1
               --report "${WORK}/bad")
expect_refused("--starts: must be in [0, 500], got 501" "${WORK}/bad" compare "${stack}" --engines own --starts 501
               --report "${WORK}/bad")
expect_refused("--starts" "${WORK}/bad" compare "${stack}" --engines own --starts nan --report "${WORK}/bad")
foreach(p -0.001 0 nan 2)
  expect_refused("--start-perturbation: must be in (0, 1] m" "${WORK}/bad" compare "${stack}" --engines own --starts 4
                 --start-perturbation ${p} --report "${WORK}/bad")
endforeach()
