# How long the longest Catch2 tests take under the sanitizers (seconds of `ctest -j2` on a clean
# clone, shared 2-core machine, load about 2), so that ctest starts them first on a fresh build
# tree: a long test started last keeps one core busy alone at the end. Once a tree has run its
# tests, ctest's own record of each test's time (Testing/Temporary/CTestCostData.txt) takes over.
# Read by ctest after the Catch2 tests are discovered and before the tests added with add_test,
# whose costs tests/CMakeLists.txt sets beside them.
set(boxpile_test_costs
  "our engine passes every check of hard scene kapla_tower" 129
  "a stack of 10 drifts less than 1e-8 m over a long run (100,000 steps unless shortened)" 12
  "our engine passes every check of hard scene pyramid_10" 46
  "our engine passes every check of hard scene pyramid_2d_20" 30
  "ODE's verdict on hard scene kapla_tower stays as measured" 21
  "Bullet's verdict on hard scene kapla_tower stays as measured" 24
  "ODE's verdict on hard scene pyramid_10 stays as measured" 8
  "Bullet's verdict on hard scene pyramid_10 stays as measured" 8
  "the hard catalogue stands under the penalty method" 32
  "our engine passes every check of hard scene jenga" 23
  "our engine passes every check of example scene pile_100" 39
  "a pile of 100 falling boxes ends with overlaps below 2 mm" 24
  "our engine passes every check of hard scene pyramid_6" 18
  "our engine passes every check of example scene pyramid" 9
  "ODE's verdict on hard scene pyramid_2d_20 stays as measured" 6
  "Bullet's verdict on hard scene pyramid_2d_20 stays as measured" 5
  "1,000 steps of pile_100 allocate nothing" 19
  "our engine passes every check of hard scene brick_wall_ram" 14
  "our impulse method's cells of the accuracy-cost sweep pass every check and stay at rest" 15
  "a run that keeps contacts at rest is the run that finds them at every step" 30)
while(boxpile_test_costs)
  list(POP_FRONT boxpile_test_costs name cost)
  set_tests_properties("${name}" PROPERTIES COST ${cost})
endwhile()
