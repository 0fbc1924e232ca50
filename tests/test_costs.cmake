# How long the longest tests take under the sanitizers (seconds, measured on a shared 2-core
# machine), so that `ctest -j2` starts them first on a fresh build tree: a long test started last
# keeps one core busy alone at the end. Once a tree has run its tests, ctest's own record of each
# test's time (Testing/Temporary/CTestCostData.txt) takes over. Read by ctest after the Catch2
# tests are discovered (tests/CMakeLists.txt); a name not found here is simply not ordered.
set(boxpile_test_costs
  "a stack of 10 drifts less than 1e-8 m in 100,000 steps" 213
  "our engine passes every check of hard scene kapla_tower" 280
  "ODE's verdict on hard scene kapla_tower stays as measured" 60
  "Bullet's verdict on hard scene kapla_tower stays as measured" 60
  "our engine passes every check of hard scene pyramid_10" 130
  "our engine passes every check of hard scene pyramid_2d_20" 85
  "our engine passes every check of hard scene jenga" 50
  "our engine passes every check of hard scene pyramid_6" 37
  "ODE's verdict on hard scene pyramid_10 stays as measured" 35
  "consumer" 35
  "the hard catalogue stands under the penalty method" 33
  "package_deb" 26
  "Bullet's verdict on hard scene pyramid_10 stays as measured" 25
  "ODE's verdict on hard scene pyramid_2d_20 stays as measured" 25
  "cli" 21
  "a pile of 100 falling boxes ends with overlaps below 2 mm" 20
  "1,000 steps of pile_100 allocate nothing" 16)
while(boxpile_test_costs)
  list(POP_FRONT boxpile_test_costs name cost)
  set_tests_properties("${name}" PROPERTIES COST ${cost})
endwhile()
