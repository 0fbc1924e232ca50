# `boxpile stability`, driven as a user would: the report, exit 0 when our engine passes, 1 when it
# fails a scene (with plots of the failing cell), 2 on bad input with no report written.
# Run with -DBOXPILE=<the boxpile executable> -DFIXTURES=<fixtures dir> -DWORK=<scratch dir>.

file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
include("${CMAKE_CURRENT_LIST_DIR}/cli_helpers.cmake")

# --- our engine passes: exit 0 ---
run_boxpile(0 stability --engines own,bullet --scenes "${FIXTURES}/hard/flat_drop.json"
            "${FIXTURES}/hard/heavy_on_light_100.json" --report "${WORK}/pass")
expect_contains("${out}" "our engine (own) passes every scene (2)")
expect_contains("${out}" "bullet fails 2 of 2 scenes")
expect_contains("${err}" "[1/4] flat_drop")
expect_contains("${err}" "left")
foreach(f stability.json stability.md)
  if(NOT EXISTS "${WORK}/pass/${f}")
    fail("stability: ${f} missing from the report")
  endif()
endforeach()
file(READ "${WORK}/pass/stability.json" report)
expect_length("${report}" 4 cells)
expect_json("${report}" "flat_drop" cells 0 scene)
expect_json("${report}" "own" cells 0 engine)
expect_json("${report}" "ON" cells 0 passed)
expect_json("${report}" "no_turning" cells 0 checks 3 name)
expect_match("${report}" "^[0-9.e+-]+$" cells 0 us_per_step)
file(READ "${WORK}/pass/stability.md" md)
expect_contains("${md}" "| flat_drop | 1 | pass: ")

# --- our engine fails a scene: exit 1, the failing cell plotted ---
file(WRITE "${WORK}/falls.json" [=[
{"name": "falls", "note": "A box dropped 1 m whose checks say it must stay at rest: it cannot.",
 "ground": {}, "bodies": [{"name": "box", "mass": 1, "half_extents": [0.5, 0.5, 0.5], "position": [0, 0, 1.5]}],
 "time": {"dt": 0.01, "duration": 0.5},
 "checks": {"rest": {"max_move": 0.001}}}
]=])
run_boxpile(1 stability --engines own --scenes "${WORK}/falls.json" --report "${WORK}/fail")
expect_contains("${out}" "FAIL falls in own")
expect_contains("${out}" "our engine (own) fails 1 of 1 scene")

# --- the summary speaks only of the engines that ran, and of "the hard scenes" only when it ran
#     them all ---
run_boxpile(0 stability --engines ode --scenes "${FIXTURES}/hard/flat_drop.json" --report "${WORK}/ode_only")
expect_contains("${out}" "ode fails 1 of 1 scene")
string(FIND "${out}" "our engine" at)
if(NOT at EQUAL -1)
  fail("stability --engines ode speaks of our engine:\n${out}")
endif()
file(READ "${WORK}/ode_only/stability.md" md)
expect_contains("${md}" "# Stability of 1 scene\n")
string(FIND "${md}" "hard scenes" at)
if(NOT at EQUAL -1)
  fail("stability.md of one scene speaks of the hard scenes:\n${md}")
endif()
file(READ "${WORK}/ode_only/stability.json" report)
expect_json("${report}" "OFF" whole_catalogue)
foreach(f falls_own_energy.svg falls_own_kinetic.svg falls_own_energy.dat)
  if(NOT EXISTS "${WORK}/fail/${f}")
    fail("stability: plot ${f} of the failing cell missing")
  endif()
endforeach()

# --- bad input: exit 2, nothing written ---
run_boxpile(2 stability --scenes "${WORK}/missing.json" --report "${WORK}/bad1")
expect_contains("${err}" "missing.json: cannot open")
run_boxpile(2 stability --engines own,odee --scenes "${WORK}/falls.json" --report "${WORK}/bad2")
expect_contains("${err}" "odee")
file(WRITE "${WORK}/a_file" "not a directory")
run_boxpile(2 stability --engines own --scenes "${WORK}/falls.json" --report "${WORK}/a_file")
expect_contains("${err}" "not a directory")
file(WRITE "${WORK}/bad_check.json" [=[
{"name": "bad", "ground": {}, "bodies": [{"name": "box", "mass": 1, "half_extents": [0.5, 0.5, 0.5], "position": [0, 0, 0.5]}],
 "time": {"dt": 0.01, "duration": 0.1}, "checks": {"rest": {"max_mve": 0.001}}}
]=])
run_boxpile(2 stability --engines own --scenes "${WORK}/bad_check.json" --report "${WORK}/bad3")
expect_contains("${err}" "checks.rest: unknown key \"max_mve\"")
foreach(d bad1 bad2 bad3)
  if(EXISTS "${WORK}/${d}")
    fail("stability: ${d} was written for bad input")
  endif()
endforeach()
