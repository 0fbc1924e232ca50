# Bad input and unusable outputs from the command line: exit codes, messages, and that nothing is
# written, replaced or left behind. Run by ctest as:
#   cmake -DBOXPILE=... -DFIXTURES=... -DWORK=... -P cli_reliability_test.cmake
cmake_minimum_required(VERSION 3.25)
include(${CMAKE_CURRENT_LIST_DIR}/cli_helpers.cmake)

file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
set(stack "${FIXTURES}/scenes/stack_5.json")
set(fall "${FIXTURES}/scenes/free_fall.json")

# No staging file or directory (".NAME.tmp-XXXXXX") may be left in a directory.
function(expect_no_staging dir)
  file(GLOB leftovers LIST_DIRECTORIES true "${dir}/.*.tmp-*")
  if(leftovers)
    fail("staging left behind: ${leftovers}")
  endif()
endfunction()

# --- outputs: refused before the run, never replaced ---------------------------------------
run_boxpile(2 run "${stack}" --engine own --out /dev/full)
expect_contains("${err}" "/dev/full: is a device node")
execute_process(COMMAND test -c /dev/full RESULT_VARIABLE still_device)
if(NOT still_device EQUAL 0)
  fail("/dev/full is no longer a character device")
endif()

execute_process(COMMAND mkfifo "${WORK}/fifo")
run_boxpile(2 run "${stack}" --engine own --out "${WORK}/fifo")
expect_contains("${err}" "is a FIFO")
execute_process(COMMAND test -p "${WORK}/fifo" RESULT_VARIABLE still_fifo)
if(NOT still_fifo EQUAL 0)
  fail("the FIFO was replaced")
endif()

file(CREATE_LINK "${WORK}/target.json" "${WORK}/link.json" SYMBOLIC)
run_boxpile(2 run "${stack}" --engine own --out "${WORK}/link.json")
expect_contains("${err}" "is a symbolic link")
if(EXISTS "${WORK}/target.json")
  fail("the link's target was written")
endif()

file(COPY_FILE "${stack}" "${WORK}/scene.json")
file(SHA256 "${WORK}/scene.json" before)
run_boxpile(2 run "${WORK}/scene.json" --engine own --out "${WORK}/scene.json")
expect_contains("${err}" "is the input file")
file(SHA256 "${WORK}/scene.json" after)
if(NOT before STREQUAL after)
  fail("--out overwrote the input scene")
endif()

run_boxpile(2 run "${stack}" --engine own --out "${WORK}")
expect_contains("${err}" "is a directory: give a file name")
run_boxpile(2 run "${stack}" --engine own --out "")
expect_contains("${err}" "--out")

# An unwritable place fails before anything else: before the scene is even read (a scene with a
# NUL byte is refused only once the output passed), so certainly before a run of 10^6 steps.
run_boxpile(2 run "${FIXTURES}/bad/nul_byte.json" --engine own --duration 4000 --out /proc/boxpile.json)
expect_contains("${err}" "cannot write in /proc")
string(FIND "${err}" "NUL byte" scene_read)
if(NOT scene_read EQUAL -1)
  fail("the scene was read before the output location was checked: ${err}")
endif()
run_boxpile(2 run "${stack}" --engine own --duration 4000 --out /proc/boxpile.json)
expect_contains("${err}" "cannot write in /proc")

# A missing parent directory is created.
run_boxpile(0 run "${fall}" --engine own --duration 0.1 --out "${WORK}/new/dir/run.json")
if(NOT EXISTS "${WORK}/new/dir/run.json")
  fail("run.json not written under new parent directories")
endif()
expect_no_staging("${WORK}/new/dir")

# compare: a report directory that holds the input, or is a link, is refused.
file(MAKE_DIRECTORY "${WORK}/holds_input")
file(COPY_FILE "${stack}" "${WORK}/holds_input/stack.json")
run_boxpile(2 compare "${WORK}/holds_input/stack.json" --engines own --report "${WORK}/holds_input")
expect_contains("${err}" "holds the input file")
file(CREATE_LINK "${WORK}/elsewhere" "${WORK}/report_link" SYMBOLIC)
run_boxpile(2 compare "${stack}" --engines own --report "${WORK}/report_link")
expect_contains("${err}" "is a symbolic link")

# --- numbers and time settings -------------------------------------------------------------
foreach(case "--dt;nan;--dt: must be a number in (0, 1] s, got nan"
             "--duration;nan;--duration: must be a finite number >= 0 s, got nan"
             "--dt;1e-300;--dt: 5 s at dt 1e-300 s is 5e+300 steps, above the cap of 10000000 (--max-steps raises it)"
             "--duration;1e300;--duration: 1e+300 s at dt 0.00416667 s is 2.4e+302 steps"
             "--dt;0;must be a number in (0, 1] s"
             "--duration;-1;must be a finite number >= 0 s")
  list(GET case 0 flag)
  list(GET case 1 value)
  list(GET case 2 message)
  run_boxpile(2 run "${stack}" --engine own ${flag} ${value})
  expect_contains("${err}" "${message}")
  run_boxpile(2 compare "${stack}" --engines own ${flag} ${value} --report "${WORK}/time_report")
  expect_contains("${err}" "${message}")
endforeach()
if(EXISTS "${WORK}/time_report")
  fail("compare wrote a report for bad time settings")
endif()
expect_no_staging("${WORK}")

# The caps, and the flags that raise them.
run_boxpile(2 run "${FIXTURES}/bad/runaway_duration.json" --engine own)
expect_contains("${err}" "runaway_duration.json: time.duration: 1e+12 s")
run_boxpile(2 run "${fall}" --engine own --dt 0.001 --duration 20 --max-steps 10000)
expect_contains("${err}" "above the cap of 10000 (--max-steps raises it)")
run_boxpile(0 run "${fall}" --engine own --dt 0.001 --duration 20 --max-steps 20000)
expect_contains("${out}" "20000 steps")
run_boxpile(2 run "${FIXTURES}/scenes/pile_100.json" --engine own --max-bodies 10)
expect_contains("${err}" "bodies: 100 bodies, above the cap of 10 (--max-bodies raises it)")
run_boxpile(0 run "${FIXTURES}/scenes/pile_100.json" --engine own --max-bodies 100 --duration 0.01)
run_boxpile(2 run "${stack}" --engine ode --iterations 1000000000)
expect_contains("${err}" "--iterations: must be in [1, 1000], got 1000000000 (--max-iterations raises the cap)")
run_boxpile(0 run "${stack}" --engine ode --iterations 2000 --max-iterations 2000 --duration 0.01)

# --- smaller ones --------------------------------------------------------------------------
run_boxpile(2 compare "${stack}" --engines own,own --report "${WORK}/twice")
expect_contains("${err}" "--engines: \"own\" is listed twice")
run_boxpile(2 contacts "${FIXTURES}/contacts/touching.json" --engines own,ode,own)
expect_contains("${err}" "--engines: \"own\" is listed twice")
# A range error says its range plainly (CLI11's PositiveNumber printed DBL_MAX in 309 digits).
run_boxpile(2 run "${stack}" --engine own --every 0)
string(LENGTH "${err}" length)
if(length GREATER 200)
  fail("a range error of ${length} characters: ${err}")
endif()
expect_contains("${err}" "--every: Value 0 not in range 1 to 2147483647")
run_boxpile(2 run "${FIXTURES}/bad/nul_byte.json" --engine own)
expect_contains("${err}" "a NUL byte at line 2, column 1")
run_boxpile(2 run "${FIXTURES}/bad/control_name.json" --engine own)
expect_contains("${err}" "\"b\\x1b[2J\"")
string(ASCII 27 escape)
string(FIND "${err}" "${escape}" raw_escape)
if(NOT raw_escape EQUAL -1)
  fail("a raw escape character was echoed")
endif()
run_boxpile(2 run "${FIXTURES}/bad/blank_name.json" --engine own)
expect_contains("${err}" "must not be only white space")
foreach(bad huge_normal huge_orientation huge_angular_velocity tiny_mass)
  run_boxpile(2 run "${FIXTURES}/bad/${bad}.json" --engine ode)
  expect_contains("${err}" "boxpile: error: ${FIXTURES}/bad/${bad}.json:")
endforeach()

# The exit codes are documented in --help.
run_boxpile(0 --help)
expect_contains("${out}" "Exit codes: 0 success; 1 a run that went wrong")

# --- interruption and fatal signals leave no staging --------------------------------------
# signal_run(<signal> <expected exit> <output that must not appear> args...): starts boxpile with
# the arguments (none with spaces), sends the signal once the output's staging file or directory
# (".NAME.tmp-XXXXXX") exists (so boxpile's handlers are in place: no guess of how long start-up
# takes under load), checks the exit code, that the output is absent and that its directory holds
# no staging. A shell's background job starts with SIGINT ignored, so a signal sent before the
# handlers are installed would be lost and the run would go on to write its output.
function(signal_run signal expected output)
  list(JOIN ARGN " " args)
  get_filename_component(dir "${output}" DIRECTORY)
  set(staged "ls -A '${dir}' 2>/dev/null | grep -q '^[.].*[.]tmp-'")
  execute_process(COMMAND sh -c "\"${BOXPILE}\" ${args} & pid=$!
    while kill -0 $pid 2>/dev/null && ! ${staged}; do sleep 0.05; done
    kill -${signal} $pid; wait $pid"
                  RESULT_VARIABLE code ERROR_VARIABLE stderr)
  if(NOT code EQUAL expected)
    fail("${signal} during boxpile ${args}: exit ${code}, expected ${expected}\n${stderr}")
  endif()
  if(EXISTS "${output}")
    fail("${signal} during boxpile ${args}: ${output} written")
  endif()
  expect_no_staging("${dir}")
endfunction()

# SIGINT during a long run: exit 130 (128 + SIGINT), nothing written.
# (Whether the signal lands before the first step or during the run, the answer is the same; the
# unit test "SIGINT inside an InterruptScope ..." covers the polled path alone.)
signal_run(INT 130 "${WORK}/int/run.json" run "${stack}" --engine own --duration 40000 --out "${WORK}/int/run.json")
# SIGABRT (what a failed assertion in an engine raises) during compare: the process dies of it
# (128 + SIGABRT), and the staging directory goes with it.
signal_run(ABRT 134 "${WORK}/abrt/report" compare "${stack}" --engines own --duration 40000 --report "${WORK}/abrt/report")
