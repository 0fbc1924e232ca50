# `cpack -G DEB` in the build folder: a Debian package of everything `cmake --install` installs,
# under /usr. Run-time libraries are found by dpkg-shlibdeps; the headers need the development
# packages of the libraries they include.
set(CPACK_PACKAGE_NAME boxpile)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_CONTACT "boxpile maintainers <boxpile@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "Boxes on a ground plane in our own simulator, checked against ODE and Bullet")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "libeigen3-dev, nlohmann-json3-dev, libode-dev, libbullet-dev, libmujoco-dev, libdart-dev, libdart-collision-ode-dev, pkg-config")
set(CPACK_DEBIAN_PACKAGE_SECTION science)
include(CPack)
