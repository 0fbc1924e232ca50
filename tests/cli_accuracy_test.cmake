# `boxpile accuracy`, driven as a user would: the report (accuracy.json in the documented shape,
# accuracy.md, the plots' data), and exit 2 on bad input with nothing written.
# Run with -DBOXPILE=<the boxpile executable> -DFIXTURES=<fixtures dir> -DWORK=<scratch dir>.

file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
include("${CMAKE_CURRENT_LIST_DIR}/cli_helpers.cmake")

# --- a report: our engine on the slide to a stop at two steps ---
run_boxpile(0 accuracy "${FIXTURES}/analytic/slide_to_stop.json" --engines own --dt 0.0166666666666667,0.00833333333333333
            --repetitions 1 --report "${WORK}/report")
expect_contains("${out}" "slide_to_stop (truth: analytic)")
foreach(f accuracy.json accuracy.md error_dt_slide_to_stop.dat error_cost_slide_to_stop.dat)
  expect_exists("${WORK}/report/${f}")
endforeach()
file(READ "${WORK}/report/accuracy.json" report)
expect_json("${report}" "analytic" scenes 0 truth)
expect_json("${report}" "own" scenes 0 engines 0 engine)
expect_length("${report}" 2 scenes 0 engines 0 cells)
expect_match("${report}" "^0\\.0248" scenes 0 engines 0 cells 0 error)
expect_match("${report}" "^0\\.99" scenes 0 engines 0 order)
expect_match("${report}" "^[0-9.e+-]+$" scenes 0 engines 0 cells 1 us_per_sim_s)

# --- bad input: exit 2, nothing written ---
expect_refused("--dt" "${WORK}/bad" accuracy "${FIXTURES}/analytic/slide_to_stop.json" --engines own --dt 0,0.01
               --report "${WORK}/bad")
expect_refused("unknown engine" "${WORK}/bad" accuracy "${FIXTURES}/analytic/slide_to_stop.json" --engines owm
               --report "${WORK}/bad")
expect_refused("--truth" "${WORK}/bad" accuracy "${FIXTURES}/analytic/slide_to_stop.json" --engines own --truth exact
               --report "${WORK}/bad")
expect_refused("pyramid.json: truth: states no truth" "${WORK}/bad" accuracy "${FIXTURES}/scenes/pyramid.json"
               --engines own --truth analytic --report "${WORK}/bad")
expect_refused("--iteration-scale" "${WORK}/bad" accuracy "${FIXTURES}/analytic/slide_to_stop.json" --engines own
               --iteration-scale 0 --report "${WORK}/bad")
file(WRITE "${WORK}/untrue.json" [=[
{"name": "untrue", "ground": {}, "bodies": [{"name": "box", "mass": 1, "half_extents": [0.5, 0.5, 0.5], "position": [0, 0, 0.5]}],
 "time": {"dt": 0.01, "duration": 0.5}, "truth": {"final_positions": {"bx": [0, 0, 0.5]}}}
]=])
expect_refused("untrue.json: truth.final_positions.bx: no body named \"bx\"" "${WORK}/bad" accuracy "${WORK}/untrue.json"
               --engines own --report "${WORK}/bad")

# --- --starts: the outcome statistics per scene in accuracy.json (docs/accuracy.md) ---
run_boxpile(0 accuracy "${FIXTURES}/analytic/slide_to_stop.json" --engines own,ode --dt 0.0166666666666667,0.00833333333333333
            --repetitions 1 --starts 4 --report "${WORK}/starts")
expect_contains("${out}" "outcomes over 4 starts, own vs ode: within chaos")
file(READ "${WORK}/starts/accuracy.json" report)
expect_json("${report}" 4 scenes 0 outcomes starts)
expect_json("${report}" 0.001 scenes 0 outcomes perturbation)
expect_match("${report}" "^0\\.00416666" scenes 0 outcomes dt)
expect_length("${report}" 5 scenes 0 outcomes measures)
expect_length("${report}" 2 scenes 0 outcomes engines)
expect_length("${report}" 4 scenes 0 outcomes engines 1 samples com_shift)
# Moved 1 mm across gravity or not, the box slides 0.911 m (ODE at the scene's 1/240 s) from every start.
expect_match("${report}" "^0\\.9111" scenes 0 outcomes engines 1 summary com_shift mean)
expect_json("${report}" "within chaos" scenes 0 outcomes pairs 0 verdict)
expect_length("${report}" 5 scenes 0 outcomes pairs 0 tests)
expect_refused("--starts: must be in [0, 500], got -3" "${WORK}/bad" accuracy "${FIXTURES}/analytic/slide_to_stop.json"
               --engines own --starts -3 --report "${WORK}/bad")
foreach(p -1e-3 nan)
  expect_refused("--start-perturbation: must be in (0, 1] m" "${WORK}/bad" accuracy "${FIXTURES}/analytic/slide_to_stop.json"
                 --engines own --starts 4 --start-perturbation ${p} --report "${WORK}/bad")
endforeach()
# The step is accuracy's own (--dt): an engine's own step through --set is refused, naming it.
expect_refused("--set: own.dt" "${WORK}/bad" accuracy "${FIXTURES}/analytic/slide_to_stop.json" --engines own
               --set own.dt=0.01 --report "${WORK}/bad")
