# How long the longest Catch2 tests take under the sanitizers (seconds of `ctest -j2` on a clean
# clone, shared 2-core machine, load about 3), so that ctest starts them first on a fresh build
# tree: a long test started last keeps one core busy alone at the end. Once a tree has run its
# tests, ctest's own record of each test's time (Testing/Temporary/CTestCostData.txt) takes over.
# Read by ctest after the Catch2 tests are discovered and before the tests added with add_test,
# whose costs tests/CMakeLists.txt sets beside them.
set(boxpile_test_costs
  "our engine passes every check of hard scene kapla_tower" 342
  "a stack of 10 drifts less than 1e-8 m in 100,000 steps" 268
  "our engine passes every check of hard scene pyramid_10" 126
  "our engine passes every check of hard scene pyramid_2d_20" 88
  "ODE's verdict on hard scene kapla_tower stays as measured" 73
  "Bullet's verdict on hard scene kapla_tower stays as measured" 69
  "ODE's verdict on hard scene pyramid_10 stays as measured" 38
  "Bullet's verdict on hard scene pyramid_10 stays as measured" 36
  "the hard catalogue stands under the penalty method" 33
  "our engine passes every check of hard scene jenga" 30
  "a pile of 100 falling boxes ends with overlaps below 2 mm" 28
  "our engine passes every check of hard scene pyramid_6" 25
  "ODE's verdict on hard scene pyramid_2d_20 stays as measured" 23
  "Bullet's verdict on hard scene pyramid_2d_20 stays as measured" 23
  "1,000 steps of pile_100 allocate nothing" 23
  "our engine passes every check of hard scene brick_wall_ram" 19
  "our impulse method's cells of the accuracy-cost sweep pass every check and stay at rest" 15)
while(boxpile_test_costs)
  list(POP_FRONT boxpile_test_costs name cost)
  set_tests_properties("${name}" PROPERTIES COST ${cost})
endwhile()
