# `cpack -G DEB` in the build tree builds ugv_<version>_amd64.deb for Debian 12.
install(FILES ${CMAKE_SOURCE_DIR}/README.md DESTINATION share/doc/ugv)
install(DIRECTORY ${CMAKE_SOURCE_DIR}/docs/ DESTINATION share/doc/ugv FILES_MATCHING PATTERN "*.md")

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME ugv)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_PACKAGE_CONTACT "UGV perception team <ugv@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "UGV terrain perception stack: LMS, servo, DGPS and IMU daemons, pose and terrain map")
set(CPACK_DEBIAN_PACKAGE_SECTION misc)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
# Shared-library dependencies found by dpkg-shlibdeps, plus what the units run.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "liblcm-bin, systemd")
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "liblcm-java, default-jre-headless, libjchart2d-java")

# conffiles: dpkg asks before replacing an edited /etc/ugv/*.toml.
set(conffiles "${CMAKE_BINARY_DIR}/debian/conffiles")
string(REPLACE ";" "\n" conffile_lines "${UGV_CONFFILES}")
file(WRITE ${conffiles} "${conffile_lines}\n")
configure_file(${CMAKE_SOURCE_DIR}/cmake/debian/postinst ${CMAKE_BINARY_DIR}/debian/postinst COPYONLY)
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA "${conffiles};${CMAKE_BINARY_DIR}/debian/postinst")
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION TRUE)
# The tests package what is built; installing must not rebuild the world first.
set(CMAKE_SKIP_INSTALL_ALL_DEPENDENCY TRUE)
include(CPack)
