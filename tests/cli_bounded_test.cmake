# Bounded memory and work in every command, and exit codes as documented (docs/reliability.md,
# "What a hostile-input probe found"): the caps of every command, inputs that are no regular file
# or too large, messages of bounded size, refused runs that leave no folders, the values that used
# to be accepted and ignored, and the sweep's workers under Ctrl-C and SIGKILL. Run by ctest as:
#   cmake -DBOXPILE=... -DFIXTURES=... -DWORK=... -P cli_bounded_test.cmake
cmake_minimum_required(VERSION 3.25)
include(${CMAKE_CURRENT_LIST_DIR}/cli_helpers.cmake)

file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
set(stack "${FIXTURES}/scenes/stack_5.json")
set(rest "${FIXTURES}/scenes/box_at_rest.json")

function(expect_short text limit)
  string(LENGTH "${text}" length)
  if(length GREATER limit)
    string(SUBSTRING "${text}" 0 300 head)
    fail("a message of ${length} characters (at most ${limit} expected): ${head}...")
  endif()
endfunction()

# n unit cubes; `pitch` m apart along x (0: all at one point), allow_initial_overlap set.
function(cube_scene file n pitch)
  set(bodies "")
  math(EXPR last "${n} - 1")
  foreach(i RANGE ${last})
    math(EXPR x_mm "${i} * ${pitch}")
    if(i GREATER 0)
      string(APPEND bodies ",")
    endif()
    string(APPEND bodies "{\"name\": \"b${i}\", \"mass\": 1, \"half_extents\": [0.5, 0.5, 0.5], \"position\": [${x_mm}e-3, 0, 0.5]}")
  endforeach()
  file(WRITE "${file}" "{\"name\": \"cubes\", \"ground\": {\"normal\": [0, 0, 1], \"offset\": 0}, \"allow_initial_overlap\": true,
    \"bodies\": [${bodies}], \"time\": {\"dt\": 0.01, \"duration\": 0.05}}")
endfunction()

# --- 1. the pairs a step may make ----------------------------------------------------------
# 30 cubes at one point: 435 pairs. Refused before any engine is handed the scene, in every
# engine alike, naming the cap and its flag; raised, the run goes.
cube_scene("${WORK}/heap.json" 30 0)
foreach(engine own ode bullet mujoco)
  run_boxpile(2 run "${WORK}/heap.json" --engine ${engine} --max-pairs 400)
  expect_contains("${err}" "heap.json: bodies: more than 400 pairs of bodies touch or overlap at the start")
  expect_contains("${err}" "(--max-pairs raises it")
endforeach()
# An engine over the protocol is not even started: its command would leave a file behind.
run_boxpile(2 run "${WORK}/heap.json" --engine probe --engine-cmd "probe=touch '${WORK}/probe_started' && cat"
            --max-pairs 400)
expect_contains("${err}" "more than 400 pairs of bodies touch or overlap at the start")
expect_absent("${WORK}/probe_started")
run_boxpile(2 compare "${WORK}/heap.json" --engines own --max-pairs 400 --report "${WORK}/heap_report")
expect_absent("${WORK}/heap_report")
run_boxpile(0 run "${WORK}/heap.json" --engine own --max-pairs 435)
# During a run, in our engine: ten cubes in a row 1 mm apart touch nothing at the start (no
# pair), but our contact margin (1 mm a box) makes nine pairs in step 1, above a cap of 5: exit 1
# (a run that went wrong), naming the engine, the step and the cap.
cube_scene("${WORK}/row.json" 10 1001)
run_boxpile(1 run "${WORK}/row.json" --engine own --max-pairs 5)
expect_contains("${err}" "own: step 1: more than 5 pairs of bodies touch, above the cap on the pairs a step may make (--max-pairs raises it)")
run_boxpile(0 run "${WORK}/row.json" --engine own --max-pairs 9)

# --- 2. every command applies the step cap --------------------------------------------------
run_boxpile(2 stability --engines own --scenes "${FIXTURES}/bad/runaway_duration.json" --report "${WORK}/runaway")
expect_contains("${err}" "runaway_duration.json: time.duration: 1e+12 s at dt 0.00416667 s is 240000000000000 steps, above the cap of 10000000 (--max-steps raises it)")
expect_absent("${WORK}/runaway")
foreach(case "\"duration\": 1e9;duration: 1e+09 s" "\"dt\": [1e-9];dt: 10 s at dt 1e-09 s")
  list(GET case 0 key)
  list(GET case 1 message)
  file(WRITE "${WORK}/grid.json" "{\"scenes\": [\"${rest}\"], ${key}, \"repetitions\": 1, \"engines\": {\"own\": {}}}")
  run_boxpile(2 sweep "${WORK}/grid.json" --report "${WORK}/grid_report")
  expect_contains("${err}" "grid.json: ${message}")
  expect_contains("${err}" "(--max-steps raises it)")
  expect_absent("${WORK}/grid_report")
endforeach()
# Penalty substeps are steps: 10 s at 1/240 s with 100,000 substeps is 2.4e8 steps of work.
file(READ "${rest}" text)
string(REPLACE "\"time\"" "\"solver\": {\"method\": \"penalty\"}, \"time\"" text "${text}")
file(WRITE "${WORK}/penalty.json" "${text}")
run_boxpile(2 run "${WORK}/penalty.json" --engine own --set substeps=100000)
expect_contains("${err}" "own: 2400 steps of 100000 penalty substeps each, above the cap of 10000000 steps")
run_boxpile(0 run "${WORK}/penalty.json" --engine own --set substeps=1000 --duration 0.01)

# --- 8. exit codes: a flag's fault is exit 2 naming the flag --------------------------------
run_boxpile(2 run "${WORK}/penalty.json" --engine own --dt 1)
expect_contains("${err}" "boxpile: error: --dt: own: dt 1 s breaks the penalty method's stability bound")
run_boxpile(2 compare "${stack}" --engines own-penalty --dt 1 --report "${WORK}/unstable")
expect_contains("${err}" "--dt: own-penalty: dt 1 s breaks")
# SIGTERM outside a run (here `contacts --serve` waiting for its first query) exits 130 as inside
# one, not by the signal (143): sent once the handler is installed (SigCgt holds bit 15).
execute_process(COMMAND mkfifo "${WORK}/serve_fifo")
execute_process(COMMAND sh -c "exec 3<>'${WORK}/serve_fifo'; \"${BOXPILE}\" contacts --serve <&3 & pid=$!
    while kill -0 $pid 2>/dev/null && [ $(( 0x$(awk '/SigCgt/ {print $2}' /proc/$pid/status) & 0x4000 )) -eq 0 ]; do sleep 0.05; done
    kill -TERM $pid; wait $pid"
                RESULT_VARIABLE code ERROR_VARIABLE stderr)
if(NOT code EQUAL 130)
  fail("SIGTERM to contacts --serve: exit ${code}, expected 130\n${stderr}")
endif()
# CLI11's own errors get our prefix and say where they arose; one line each.
run_boxpile(2 run "${stack}")
expect_contains("${err}" "boxpile: error: run: --engine is required")
run_boxpile(2 --no-such-flag)
expect_contains("${err}" "boxpile: error: $: ")
run_boxpile(2 --version junk)
expect_contains("${err}" "boxpile: error: $: ")

# --- 4. sweep-merge refuses an output that is one of its inputs -----------------------------
foreach(shard s1 s2)
  file(WRITE "${WORK}/${shard}/sweep.json" "{\"kept\": \"${shard}\"}")
endforeach()
run_boxpile(2 sweep-merge "${WORK}/s1" "${WORK}/s2" --report "${WORK}/s1")
expect_contains("${err}" "holds the input file")
file(READ "${WORK}/s1/sweep.json" kept)
if(NOT kept STREQUAL "{\"kept\": \"s1\"}")
  fail("sweep-merge replaced its own input: ${kept}")
endif()

# --- 6. an empty folder is a usable report directory, "." included ---------------------------
file(MAKE_DIRECTORY "${WORK}/here")
execute_process(COMMAND "${BOXPILE}" compare "${rest}" --engines own --duration 0.05 --report .
                WORKING_DIRECTORY "${WORK}/here" RESULT_VARIABLE code ERROR_VARIABLE stderr OUTPUT_QUIET)
if(NOT code EQUAL 0)
  fail("compare --report . in an empty folder: exit ${code}\n${stderr}")
endif()
expect_exists("${WORK}/here/report.json")
file(GLOB leftovers LIST_DIRECTORIES true "${WORK}/here/.*" "${WORK}/.here.tmp-*")
if(leftovers)
  fail("staging left behind: ${leftovers}")
endif()

# --- 7. inputs: regular files of bounded size ----------------------------------------------
run_boxpile(2 run /dev/zero --engine own)
expect_contains("${err}" "/dev/zero: cannot open: not a regular file")
run_boxpile(2 contacts /dev/zero)
expect_contains("${err}" "/dev/zero: cannot open: not a regular file")
execute_process(COMMAND mkfifo "${WORK}/input_fifo")
# A FIFO without a writer used to block forever: refused at once (the timeout fails the test).
execute_process(COMMAND "${BOXPILE}" run "${WORK}/input_fifo" --engine own TIMEOUT 20
                RESULT_VARIABLE code ERROR_VARIABLE stderr)
if(NOT code EQUAL 2)
  fail("run of a FIFO: exit ${code}\n${stderr}")
endif()
expect_contains("${stderr}" "input_fifo: cannot open: not a regular file")
file(SIZE "${stack}" stack_bytes)
run_boxpile(2 run "${stack}" --engine own --max-input-bytes 100)
expect_contains("${err}" "stack_5.json: ${stack_bytes} bytes, above the cap of 100 bytes (--max-input-bytes raises it)")

# --- 9. values accepted and ignored, or misread ---------------------------------------------
foreach(timeout nan 1e300 1e-300 0 -1)
  run_boxpile(2 conform --collider cat --timeout ${timeout} --report "${WORK}/conform")
  expect_contains("${err}" "--timeout: must be a number of seconds in [0.001, 86400]")
  expect_short("${err}" 200)
endforeach()
run_boxpile(2 conform --collider cat --seed -1 --report "${WORK}/conform")
expect_contains("${err}" "--seed")
expect_absent("${WORK}/conform")
run_boxpile(2 run "${stack}" --engine own --dt "")
expect_contains("${err}" "boxpile: error: run: --dt: 1 required FLOAT missing")
run_boxpile(2 run "${stack}" --engine own --iterations 5)
expect_contains("${err}" "--iterations: engine \"own\" has no setting \"iterations\"")
run_boxpile(2 run "${stack}" --engine bullet --set ode.stepper=step)
expect_contains("${err}" "engine \"ode\" is not running")
run_boxpile(2 run "${stack}" --engine ode --set erp=0.2 --set erp=0.8)
expect_contains("${err}" "setting \"erp\" is given twice")
run_boxpile(2 run "${stack}" --engine ode --set erp=0.2 --set ode.erp=0.8)
expect_contains("${err}" "setting \"erp\" is given twice")
run_boxpile(2 compare "${stack}" --engines own,,ode --report "${WORK}/commas")
expect_contains("${err}" "--engines: an empty name in \"own,,ode\"")
run_boxpile(2 compare "${stack}" --engines , --report "${WORK}/commas")
expect_absent("${WORK}/commas")
run_boxpile(2 compare "${stack}" --engines own,own-impulse --report "${WORK}/twice")
expect_contains("${err}" "--engines: \"own\" and \"own-impulse\" are one engine on")
expect_absent("${WORK}/twice")

# --- 10. messages of bounded size ------------------------------------------------------------
string(REPEAT "k" 100000 long_key)
file(WRITE "${WORK}/long_key.json" "{\"${long_key}\": 1, \"bodies\": []}")
run_boxpile(2 run "${WORK}/long_key.json" --engine own)
expect_contains("${err}" "... (100000 characters)")
expect_short("${err}" 1000)
# Names and commands on the command line are quoted as briefly (an unknown engine, --engine-cmd).
run_boxpile(2 run "${stack}" --engine "${long_key}")
expect_contains("${err}" "unknown engine \"kkkk")
expect_short("${err}" 1000)
run_boxpile(2 run "${stack}" --engine own --engine-cmd "${long_key}")
expect_contains("${err}" "is not NAME=COMMAND")
expect_short("${err}" 1000)
string(REPEAT "t" 100000 long_token)
file(WRITE "${WORK}/long_token.json" "{\"bodies\": ${long_token}}")
run_boxpile(2 run "${WORK}/long_token.json" --engine own)
expect_contains("${err}" "JSON syntax error")
expect_short("${err}" 1000)

# --- 11. refused runs leave no folders ------------------------------------------------------
run_boxpile(2 run "${stack}" --engine own --dt 0 --out "${WORK}/td/p/q/out.json")
expect_absent("${WORK}/td")
run_boxpile(2 compare "${stack}" --engines own --dt 0 --report "${WORK}/te/p/report")
expect_absent("${WORK}/te")

# --- 12. messages that said less than they meant ---------------------------------------------
run_boxpile(2 run "${rest}" --engine own --dt 1 --duration 10000001)
expect_contains("${err}" "is 10000001 steps, above the cap of 10000000")
run_boxpile(2 run "${rest}" --engine own --dt 4.94e-324)
expect_contains("${err}" "more steps than a double counts")
run_boxpile(2 stability --engines own --scenes "${WORK}/heap.json" --max-pairs 10 --report "${WORK}/st")
expect_contains("${err}" "(--max-pairs raises it")

# --- 5. the sweep's workers: Ctrl-C to the process group, SIGKILL of the parent ---------------
# A grid of two long cells (20 s of the pile each, a minute or more: far longer than the test waits).
file(WRITE "${WORK}/long_grid.json" "{\"scenes\": [\"${FIXTURES}/scenes/pile_100.json\"], \"duration\": 20, \"repetitions\": 1,
  \"engines\": {\"own\": {}, \"ode\": {}}}")
# `setsid`: boxpile leads its own process group, which `kill -INT -PID` signals as a terminal does.
set(staged "ls -A '${WORK}' | grep -q '^[.]sw[.]tmp-'")
execute_process(COMMAND sh -c "setsid \"${BOXPILE}\" sweep '${WORK}/long_grid.json' --jobs 2 --report '${WORK}/sw' & pid=$!
    while kill -0 $pid 2>/dev/null && ! ${staged}; do sleep 0.05; done
    sleep 0.5; kill -INT -$pid; wait $pid"
                RESULT_VARIABLE code ERROR_VARIABLE stderr)
if(NOT code EQUAL 130)
  fail("SIGINT to sweep --jobs 2: exit ${code}, expected 130\n${stderr}")
endif()
expect_contains("${stderr}" "boxpile: interrupted: no report written")
string(FIND "${stderr}" "worker" worker_message)
if(NOT worker_message EQUAL -1)
  fail("an interrupt was reported as a worker's failure:\n${stderr}")
endif()
expect_absent("${WORK}/sw")
# SIGKILL of the parent: its workers die with it (none of its process group is left a second
# later; a zombie not yet reaped is dead), and the next run names the staging folder it could not remove.
execute_process(COMMAND sh -c "setsid \"${BOXPILE}\" sweep '${WORK}/long_grid.json' --jobs 2 --report '${WORK}/sw' & pid=$!
    while kill -0 $pid 2>/dev/null && ! ${staged}; do sleep 0.05; done
    sleep 0.5; kill -KILL $pid; wait $pid; sleep 1
    if ps -e -o pgid=,stat= | awk -v g=$pid '$1 == g && $2 !~ /^Z/ {found = 1} END {exit !found}'; then echo alive; kill -KILL -$pid; fi"
                OUTPUT_VARIABLE alive ERROR_QUIET)
if(alive MATCHES "alive")
  fail("the sweep's workers outlived their parent's SIGKILL")
endif()
run_boxpile(2 sweep "${WORK}/long_grid.json" --report "${WORK}/sw" --max-steps 10)
expect_contains("${err}" "is the staging of an earlier run that was killed")
file(GLOB abandoned LIST_DIRECTORIES true "${WORK}/.sw.tmp-*")
file(REMOVE_RECURSE ${abandoned})
