# `boxpile compare`, driven as a user would: the report it writes, its summary, and bad input
# (exit 2, a clear message, and no report directory, not even a half-written one).
# Run with -DBOXPILE=<the boxpile executable> -DFIXTURES=<fixtures dir> -DWORK=<scratch dir>.

file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
include("${CMAKE_CURRENT_LIST_DIR}/cli_helpers.cmake")

function(expect_absent path)
  if(EXISTS "${path}")
    fail("${path} exists: a report was written for bad input")
  endif()
endfunction()

set(stack "${FIXTURES}/scenes/stack_5.json")

# --- a report ---
run_boxpile(0 compare "${stack}" --engines ode,bullet --duration 0.25 --report "${WORK}/report")
expect_contains("${out}" "us per step")
expect_contains("${out}" "ode vs bullet")
expect_contains("${out}" "report: ")
expect_contains("${out}" "report/report.md")
expect_contains("${err}" "[1/4] ode")
foreach(f report.json report.md energy.svg energy.dat energy.gp penetration.svg stack_height.svg
          position_difference.svg)
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
# Run again into the same directory: the previous report is replaced whole.
run_boxpile(0 compare "${stack}" --engines bullet --duration 0.1 --report "${WORK}/report")
file(READ "${WORK}/report/report.json" report)
string(JSON n LENGTH "${report}" engines)
if(NOT n EQUAL 1)
  fail("compare into an existing report: ${n} engines, expected the new report's 1")
endif()

# --- bad input: exit 2, a message, nothing written ---
run_boxpile(2 compare "${stack}" --engines own,physx --report "${WORK}/bad_engine")
expect_contains("${err}" "unknown engine \"physx\"; available: own, own-impulse, own-penalty, ode, bullet")
expect_absent("${WORK}/bad_engine")

run_boxpile(2 compare "${WORK}/missing.json" --report "${WORK}/bad_scene")
expect_contains("${err}" "missing.json")
expect_absent("${WORK}/bad_scene")

run_boxpile(2 compare "${FIXTURES}/bad/overlap.json" --report "${WORK}/bad_overlap")
expect_contains("${err}" "overlap.json")
expect_absent("${WORK}/bad_overlap")

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
