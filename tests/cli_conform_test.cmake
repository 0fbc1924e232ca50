# `boxpile conform` and `boxpile contacts --serve|--format`, driven as a user would.
# Run with -DBOXPILE=<the boxpile executable> -DFIXTURES=<fixtures dir> -DEXAMPLES=<examples dir>
# -DSCRIPTS=<tests/scripts> -DWORK=<scratch dir>.

file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
include("${CMAKE_CURRENT_LIST_DIR}/cli_helpers.cmake")

# --- contacts --serve: the line protocol, answered by our detector and by ODE ---
file(READ "${FIXTURES}/contacts/aligned_offset.json" aligned)
file(READ "${FIXTURES}/contacts/plane_flat.json" flat)
string(REPLACE "\n" " " aligned "${aligned}")
string(REPLACE "\n" " " flat "${flat}")
file(WRITE "${WORK}/queries.txt" "${aligned}\n\n${flat}\n")
foreach(engine own ode)
  execute_process(COMMAND "${BOXPILE}" contacts --serve --engine ${engine} INPUT_FILE "${WORK}/queries.txt"
                  RESULT_VARIABLE code OUTPUT_VARIABLE answers ERROR_VARIABLE err)
  if(NOT code EQUAL 0)
    fail("contacts --serve --engine ${engine}: exit ${code}: ${err}")
  endif()
  string(REGEX MATCHALL "[^\n]+" lines "${answers}")
  list(LENGTH lines n)
  if(NOT n EQUAL 2)
    fail("contacts --serve --engine ${engine}: ${n} answer lines for 2 queries (a blank line is skipped):\n${answers}")
  else()
    list(GET lines 0 first)
    list(GET lines 1 second)
    expect_length("${first}" 4 contacts)  # aligned_offset: a 4-point face contact
    expect_length("${second}" 4 contacts)  # plane_flat: 4 vertices on the ground
  endif()
endforeach()
file(WRITE "${WORK}/bad_line.txt" "${aligned}\n{\"a\": 1}\n")
execute_process(COMMAND "${BOXPILE}" contacts --serve INPUT_FILE "${WORK}/bad_line.txt" RESULT_VARIABLE code
                OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT code EQUAL 2)
  fail("contacts --serve with a bad line: exit ${code}, expected 2")
endif()
expect_contains("${err}" "stdin line 2")

# --- contacts --format ---
run_boxpile(0 contacts "${FIXTURES}/contacts/aligned_offset.json" --format table)
expect_contains("${out}" "against own")
expect_contains("${out}" "depth (m)")
run_boxpile(2 contacts "${FIXTURES}/contacts/aligned_offset.json" --format yaml)
run_boxpile(2 contacts --engine ode "${FIXTURES}/contacts/aligned_offset.json")  # --engine needs --serve

# --- conform: our own detector through the protocol passes ---
set(own_collider "\"${BOXPILE}\" contacts --serve")
run_boxpile(0 conform --collider "${own_collider}" --samples 300 --report "${WORK}/own")
file(READ "${WORK}/own/conform.json" report)
expect_json("${report}" ON within_gates)
expect_length("${report}" 0 failures)
expect_json("${report}" 323 queries)  # 23 fixtures and 300 pairs
expect_contains("${out}" "within the gates")
file(READ "${WORK}/own/conform.md" md)
expect_contains("${md}" "every answer was right")

# --- conform: the Python example, face axes only, is caught on crossing edges ---
run_boxpile(1 conform --collider "python3 ${EXAMPLES}/colliders/face_axes.py" --samples 300 --report "${WORK}/py")
file(READ "${WORK}/py/conform.json" report)
expect_json("${report}" OFF within_gates)
string(JSON missed GET "${report}" failures_by_kind missed count)
string(JSON normal GET "${report}" failures_by_kind normal count)
if(missed LESS 1 OR normal LESS 1)
  fail("the face-axes collider: ${missed} missed and ${normal} normal failures, expected some of each")
endif()
string(JSON first_file GET "${report}" failures 0 file)
# Every failing query is put to the registered detectors too: ours is right on each of them.
string(JSON failing LENGTH "${report}" failures)
math(EXPR last "${failing} - 1")
foreach(k RANGE ${last})
  string(JSON own_wrong LENGTH "${report}" failures ${k} detectors own)
  string(JSON ode_seen ERROR_VARIABLE no_ode LENGTH "${report}" failures ${k} detectors ode)
  if(NOT own_wrong EQUAL 0 OR no_ode)
    fail("failure ${k} of the face-axes collider: our detector judged wrong (${own_wrong}) or ODE not judged")
  endif()
endforeach()
expect_contains("${out}" "also wrong on these queries: own 0 of ${failing}, ode")
# A saved failure loads as a query, with the collider's answer beside ours.
run_boxpile(0 contacts "${WORK}/py/${first_file}" --format json)
string(JSON saved ERROR_VARIABLE no_saved GET "${out}" engines "collider (saved)")
if(no_saved)
  fail("${first_file}: no saved collider answer in `boxpile contacts`: ${out}")
endif()
# Without --out, conform writes ./boxpile-conform/ as compare writes ./boxpile-report/.
file(MAKE_DIRECTORY "${WORK}/default_out")
execute_process(COMMAND "${BOXPILE}" conform --collider "${own_collider}" --samples 5 --cases none
                WORKING_DIRECTORY "${WORK}/default_out" RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT code EQUAL 0 OR NOT EXISTS "${WORK}/default_out/boxpile-conform/conform.json")
  fail("conform without --out: exit ${code}, no boxpile-conform/conform.json\n${out}${err}")
endif()

# The same folder again replaces the report; a folder that is no conform report is refused.
run_boxpile(1 conform --collider "python3 ${EXAMPLES}/colliders/face_axes.py" --samples 10 --cases none
            --report "${WORK}/py")
file(MAKE_DIRECTORY "${WORK}/precious")
file(WRITE "${WORK}/precious/notes.txt" "mine")
run_boxpile(2 conform --collider "${own_collider}" --samples 1 --report "${WORK}/precious")

# --- conform: colliders that die, hang or answer garbage exit 2, naming what happened ---
run_boxpile(2 conform --collider "exit 3" --samples 5 --cases none --report "${WORK}/dies")
expect_contains("${err}" "exited with status 3")
run_boxpile(2 conform --collider "sleep 5" --samples 5 --cases none --timeout 0.3 --report "${WORK}/hangs")
expect_contains("${err}" "no answer")
expect_contains("${err}" "within 300 ms")
# One that closes its output but goes on running is not waited for: a second, then it is killed.
file(WRITE "${WORK}/closes.sh" "exec >&-\nsleep 60\n")
run_boxpile(2 conform --collider "exec sh ${WORK}/closes.sh" --samples 5 --cases none --report "${WORK}/closes")
expect_contains("${err}" "closed its output before answering")
file(WRITE "${WORK}/garbage.sh" "while read q\ndo echo '{\"contacts\": 5}'\ndone\n")
run_boxpile(2 conform --collider "sh ${WORK}/garbage.sh" --samples 5 --cases none --report "${WORK}/garbage")
expect_contains("${err}" "output line 1")
if(EXISTS "${WORK}/dies" OR EXISTS "${WORK}/hangs" OR EXISTS "${WORK}/closes" OR EXISTS "${WORK}/garbage")
  fail("a failed conform run left a report folder")
endif()
run_boxpile(2 conform --collider "${own_collider}" --regimes sideways --report "${WORK}/bad")
run_boxpile(2 conform --collider "${own_collider}" --cases "${WORK}/nowhere" --report "${WORK}/bad")

# --- conform: our detector behind tests/scripts/collider_wrapper.py, one change made on purpose ---
set(wrapper "python3 ${SCRIPTS}/collider_wrapper.py")
# Read and written in single precision: fails double precision's tolerances, passes float32's.
set(float_collider "${wrapper} --float32 -- ${own_collider}")
run_boxpile(1 conform --collider "${float_collider}" --samples 300 --report "${WORK}/f64")
file(READ "${WORK}/f64/conform.json" report)
string(JSON f64_failing GET "${report}" failing)
if(f64_failing LESS 150)
  fail("the float32 collider at --tolerance float64: ${f64_failing} of 323 failing, expected most")
endif()
run_boxpile(0 conform --collider "${float_collider}" --samples 300 --tolerance float32 --report "${WORK}/f32")
file(READ "${WORK}/f32/conform.json" report)
expect_json("${report}" 0 failing)
expect_json("${report}" float32 settings tolerance)
# Depths 10% short: named by their ratio, in every failing depth query.
run_boxpile(1 conform --collider "${wrapper} --depth-scale 0.9 -- ${own_collider}" --samples 300 --report "${WORK}/short")
expect_contains("${out}" "systematic: depth 0.9 of the truth in")
file(READ "${WORK}/short/conform.json" report)
expect_json("${report}" depth_ratio systematic 0 pattern)
expect_match("${report}" "^0\\.(9$|8999999|9000000)" systematic 0 value)
string(JSON depth_count GET "${report}" failures_by_kind depth count)
expect_json("${report}" ${depth_count} systematic 0 count)
file(READ "${WORK}/short/conform.md" md)
expect_contains("${md}" "## Failures by regime")
expect_contains("${md}" "## Failures by contact kind")
# Edge-edge normals reversed: named for edge-edge.
run_boxpile(1 conform --collider "${wrapper} --flip-edge-edge -- ${own_collider}" --samples 300 --report "${WORK}/flip")
expect_contains("${out}" "systematic: edge-edge normals reversed in")
file(READ "${WORK}/flip/conform.json" report)
expect_json("${report}" reversed_normals systematic 0 pattern)
expect_json("${report}" edge-edge systematic 0 contact)
string(JSON by_contact GET "${report}" by_contact edge-edge failing)
if(by_contact LESS 40)
  fail("flipped edge-edge normals: ${by_contact} failing edge-edge queries, expected the edge_edge regime's 43 at least")
endif()
# --keep bounds the saved files; the counts stay whole.
run_boxpile(1 conform --collider "${wrapper} --depth-scale 0.9 -- ${own_collider}" --samples 300 --keep 3
            --progress --report "${WORK}/kept")
file(GLOB kept "${WORK}/kept/failures/*.json")
list(LENGTH kept kept_files)
file(READ "${WORK}/kept/conform.json" report)
# The 3 worst depth failures, and any kept as the worst of another kind that fails on depth too.
string(JSON depth_saved GET "${report}" failures_by_kind depth saved)
if(depth_saved LESS 3 OR depth_saved GREATER kept_files)
  fail("--keep 3: ${depth_saved} depth failures saved, expected 3 and at most the ${kept_files} files")
endif()
expect_json("${report}" ${depth_count} failures_by_kind depth count)
string(JSON saved GET "${report}" saved)
if(kept_files GREATER 18 OR NOT kept_files EQUAL saved OR kept_files LESS 3)
  fail("--keep 3: ${kept_files} files saved (the report says ${saved}), expected 3 to 18 (3 per failure kind)")
endif()
# --progress outside a terminal: a line per tenth and the time taken.
expect_contains("${err}" "s left")
expect_contains("${err}" "queries in")
# Bad flags: exit 2, naming the flag, no report.
foreach(bad 0 -1 nan inf 1e999 float16 "")
  run_boxpile(2 conform --collider "${own_collider}" --samples 1 --tolerance "${bad}" --report "${WORK}/badtol")
  expect_contains("${err}" "--tolerance")
endforeach()
run_boxpile(2 conform --collider "${own_collider}" --samples 1 --keep -1 --report "${WORK}/badtol")
expect_contains("${err}" "--keep")
expect_absent("${WORK}/badtol")
