# `boxpile conform` and `boxpile contacts --serve|--format`, driven as a user would.
# Run with -DBOXPILE=<the boxpile executable> -DFIXTURES=<fixtures dir> -DEXAMPLES=<examples dir>
# -DWORK=<scratch dir>.

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
expect_contains("${out}" "also wrong on these queries: own 0, ode")
# A saved failure loads as a query, with the collider's answer beside ours.
run_boxpile(0 contacts "${WORK}/py/${first_file}" --format json)
string(JSON saved ERROR_VARIABLE no_saved GET "${out}" engines "collider (saved)")
if(no_saved)
  fail("${first_file}: no saved collider answer in `boxpile contacts`: ${out}")
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
