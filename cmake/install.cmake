# `cmake --install build --prefix P`: the libraries, the headers under P/include/boxpile/, the
# boxpile program, the fixtures, sweep grids and report assets under P/share/boxpile/, and the CMake package
# (find_package(boxpile) gives boxpile::sim, boxpile::scene_io, boxpile::checks, boxpile::reference,
# boxpile::judge and boxpile::validation).
include(CMakePackageConfigHelpers)

set(BOXPILE_CMAKE_INSTALL_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/boxpile)

# Each library's export name is its short name: boxpile_sim becomes boxpile::sim.
set(boxpile_libraries boxpile_sim boxpile_scene_io boxpile_checks boxpile_reference boxpile_judge boxpile_validation)
foreach(lib IN LISTS boxpile_libraries)
  string(REPLACE "boxpile_" "" short ${lib})
  set_target_properties(${lib} PROPERTIES EXPORT_NAME ${short})
endforeach()

# Libraries built with the sanitizers (BOXPILE_SANITIZE, BOXPILE_FUZZ) need the sanitizers' runtimes
# in every program that links them, a consumer of the installed package too: their link interface
# says so.
if(BOXPILE_SANITIZE OR BOXPILE_FUZZ)
  foreach(lib IN LISTS boxpile_libraries)
    target_link_options(${lib} INTERFACE -fsanitize=address,undefined)
  endforeach()
endif()

# boxpile_warnings is linked privately; static libraries still name it in their link interface,
# so it travels in the export set (it carries no flags outside the build tree).
install(TARGETS ${boxpile_libraries} boxpile_warnings EXPORT boxpileTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS boxpile RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

# Headers keep their folders: P/include/boxpile/{sim,reference,validation}/...
foreach(folder sim reference validation)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${folder}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/boxpile/${folder}
    FILES_MATCHING PATTERN "*.hpp" PATTERN "node_modules" EXCLUDE)
endforeach()
install(FILES ${PROJECT_SOURCE_DIR}/boxpile.hpp DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/boxpile)

# Data: every fixture, the sweep grids, and the web assets of any report or viewer under validation/ (page
# templates, scripts, styles, images), folder by folder: validation/replay/viewer.js goes to
# P/share/boxpile/replay/viewer.js, and a new asset file needs no change here.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/fixtures DESTINATION ${BOXPILE_DATA_INSTALL_DIR})
# The sweep grids, at the same place relative to the fixtures as in the source tree: their scene
# paths (relative to the grid file) hold, and `boxpile sweep NAME` finds them by name.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/benchmarks/grids DESTINATION ${BOXPILE_DATA_INSTALL_DIR}/benchmarks)
# The node-hosted engines: their adapters, the protocol loop they share (reference/protocol/),
# package.json and the npm packages scripts/install-deps put in reference/node_modules, where the
# data folder's reference/ has them in the build tree too.
# OPTIONAL: a tree without them installs a boxpile that lists those engines as unavailable.
foreach(folder protocol jolt rapier mujoco_wasm node_modules)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/reference/${folder} DESTINATION ${BOXPILE_DATA_INSTALL_DIR}/reference
    OPTIONAL USE_SOURCE_PERMISSIONS PATTERN "*.cpp" EXCLUDE PATTERN "*.hpp" EXCLUDE PATTERN "CMakeLists.txt" EXCLUDE)
endforeach()
install(FILES ${PROJECT_SOURCE_DIR}/reference/package.json ${PROJECT_SOURCE_DIR}/reference/package-lock.json
  DESTINATION ${BOXPILE_DATA_INSTALL_DIR}/reference OPTIONAL)
file(GLOB boxpile_validation_folders LIST_DIRECTORIES true ${PROJECT_SOURCE_DIR}/validation/*)
foreach(dir IN LISTS boxpile_validation_folders)
  file(GLOB_RECURSE assets ${dir}/*.html ${dir}/*.js ${dir}/*.css ${dir}/*.svg ${dir}/*.png)
  if(IS_DIRECTORY ${dir} AND assets)
    get_filename_component(name ${dir} NAME)
    install(DIRECTORY ${dir}/ DESTINATION ${BOXPILE_DATA_INSTALL_DIR}/${name}
      FILES_MATCHING PATTERN "*.html" PATTERN "*.js" PATTERN "*.css" PATTERN "*.svg" PATTERN "*.png")
  endif()
endforeach()

install(EXPORT boxpileTargets NAMESPACE boxpile:: DESTINATION ${BOXPILE_CMAKE_INSTALL_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/boxpileConfig.cmake.in
  ${PROJECT_BINARY_DIR}/boxpileConfig.cmake INSTALL_DESTINATION ${BOXPILE_CMAKE_INSTALL_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/boxpileConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/boxpileConfig.cmake ${PROJECT_BINARY_DIR}/boxpileConfigVersion.cmake
  DESTINATION ${BOXPILE_CMAKE_INSTALL_DIR})
