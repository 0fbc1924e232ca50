# Helpers shared by the CLI tests (cmake -P scripts): run boxpile and check what it printed.
# The including script sets BOXPILE (the executable); failures are SEND_ERRORs, so a script
# reports every failed check and then exits non-zero.

function(fail message)
  message(SEND_ERROR "${message}")
endfunction()

# run_boxpile(<expected exit code> <args...>): runs boxpile, sets out and err in the caller.
function(run_boxpile expected)
  execute_process(COMMAND "${BOXPILE}" ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE stdout
                  ERROR_VARIABLE stderr)
  if(NOT code EQUAL expected)
    fail("boxpile ${ARGN}: exit ${code}, expected ${expected}\nstdout: ${stdout}\nstderr: ${stderr}")
  endif()
  set(out "${stdout}" PARENT_SCOPE)
  set(err "${stderr}" PARENT_SCOPE)
endfunction()

function(expect_json json expected)
  string(JSON value ERROR_VARIABLE error GET "${json}" ${ARGN})
  if(error OR NOT value STREQUAL expected)
    fail("JSON ${ARGN}: got '${value}' (${error}), expected '${expected}'")
  endif()
endfunction()

# A value matching a regular expression (numbers print as "0.0", "0.5000000000000001", ...).
function(expect_match json regex)
  string(JSON value ERROR_VARIABLE error GET "${json}" ${ARGN})
  if(error OR NOT value MATCHES "${regex}")
    fail("JSON ${ARGN}: got '${value}' (${error}), expected a match of ${regex}")
  endif()
endfunction()

function(expect_length json expected)
  string(JSON value ERROR_VARIABLE error LENGTH "${json}" ${ARGN})
  if(error OR NOT value EQUAL expected)
    fail("JSON length of ${ARGN}: got '${value}' (${error}), expected ${expected}")
  endif()
endfunction()

function(expect_contains text fragment)
  string(FIND "${text}" "${fragment}" at)
  if(at EQUAL -1)
    fail("expected '${fragment}' in:\n${text}")
  endif()
endfunction()

function(expect_absent path)
  if(EXISTS "${path}")
    fail("${path} exists: output was written for bad input")
  endif()
endfunction()

function(expect_exists path)
  if(NOT EXISTS "${path}")
    fail("${path} was not written")
  endif()
endfunction()

# expect_refused(<message fragment> <path> <args...>): boxpile exits with 2 for bad input, its
# message holds the fragment, and nothing is written at the path.
function(expect_refused fragment path)
  run_boxpile(2 ${ARGN})
  expect_contains("${err}" "${fragment}")
  expect_absent("${path}")
endfunction()
