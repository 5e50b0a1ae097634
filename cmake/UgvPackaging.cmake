# `cpack -G DEB` in the build tree builds two packages for Debian 12 (docs/deploy.md "The package"):
#   ugv_<version>_amd64.deb         the stack, its programs stripped
#   ugv-dbgsym_<version>_amd64.deb  their debug information, /usr/lib/debug/.build-id/xx/yyyy.debug
# gdb and systemd-coredump find a program's symbols through its build-id.
install(FILES ${CMAKE_SOURCE_DIR}/README.md DESTINATION share/doc/ugv)
install(DIRECTORY ${CMAKE_SOURCE_DIR}/docs/ DESTINATION share/doc/ugv FILES_MATCHING PATTERN "*.md")

# Debian's own files for a native package: copyright and a compressed changelog.
set(UGV_DEBIAN_DIR ${CMAKE_BINARY_DIR}/debian)
configure_file(${CMAKE_SOURCE_DIR}/cmake/debian/changelog.in ${UGV_DEBIAN_DIR}/changelog @ONLY)
execute_process(COMMAND gzip -9nf -k ${UGV_DEBIAN_DIR}/changelog COMMAND_ERROR_IS_FATAL ANY)
foreach(pkg ugv ugv-dbgsym)
  set(comp ugv)
  if(pkg STREQUAL ugv-dbgsym)
    set(comp dbgsym)
  endif()
  install(FILES ${CMAKE_SOURCE_DIR}/cmake/debian/copyright ${UGV_DEBIAN_DIR}/changelog.gz
          DESTINATION share/doc/${pkg} COMPONENT ${comp} EXCLUDE_FROM_ALL)
endforeach()

# ugv-dbgsym: each packaged ELF file's debug sections, compressed, named by its build-id.
# Made from the unstripped build tree while CPack strips the copies in `ugv`
# (CPACK_STRIP_FILES). CPack's own CPACK_DEBIAN_DEBUGINFO_PACKAGE is not used: CMake 3.25
# writes the staging folder's absolute paths into the dbgsym md5sums.
get_property(UGV_PACKAGED_ELF GLOBAL PROPERTY UGV_PACKAGED_ELF)
set(elf_files "")
foreach(target ${UGV_PACKAGED_ELF})
  string(APPEND elf_files "\"$<TARGET_FILE:${target}>\" ")
endforeach()
install(CODE "
  foreach(elf ${elf_files})
    execute_process(COMMAND readelf -n \${elf} OUTPUT_VARIABLE notes COMMAND_ERROR_IS_FATAL ANY)
    if(NOT notes MATCHES \"Build ID: ([0-9a-f][0-9a-f])([0-9a-f]+)\")
      message(FATAL_ERROR \"\${elf} has no build-id\")
    endif()
    set(dir \"\$ENV{DESTDIR}\${CMAKE_INSTALL_PREFIX}/lib/debug/.build-id/\${CMAKE_MATCH_1}\")
    file(MAKE_DIRECTORY \"\${dir}\")
    execute_process(COMMAND objcopy --only-keep-debug --compress-debug-sections=zlib \${elf} \${dir}/\${CMAKE_MATCH_2}.debug
                    COMMAND_ERROR_IS_FATAL ANY)
    file(CHMOD \${dir}/\${CMAKE_MATCH_2}.debug PERMISSIONS OWNER_READ OWNER_WRITE GROUP_READ WORLD_READ)
  endforeach()" COMPONENT dbgsym EXCLUDE_FROM_ALL)

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME ugv)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_PACKAGE_CONTACT "UGV perception team <ugv-team@example.com>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "terrain perception stack for an unmanned ground vehicle")
set(CPACK_PACKAGE_DESCRIPTION "Daemons for a SICK LMS 2xx on a nodding servo, a DGPS receiver and an IMU\n\
over LCM multicast, with the pose estimate, the terrain map, the traversability\n\
maps, their systemd units, udev rules and tools to record and inspect logs.")
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_ALL ugv dbgsym)
set(CPACK_COMPONENTS_GROUPING IGNORE)
set(CPACK_STRIP_FILES TRUE)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
set(CPACK_DEBIAN_UGV_PACKAGE_NAME ugv)
set(CPACK_DEBIAN_UGV_PACKAGE_SECTION misc)
# Shared-library dependencies found by dpkg-shlibdeps, plus what the units and rules run.
set(CPACK_DEBIAN_UGV_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_UGV_PACKAGE_DEPENDS "liblcm-bin, systemd, udev")
set(CPACK_DEBIAN_UGV_PACKAGE_RECOMMENDS "liblcm-java, default-jre-headless, libjchart2d-java")
set(CPACK_DEBIAN_DBGSYM_PACKAGE_NAME ugv-dbgsym)
set(CPACK_DEBIAN_DBGSYM_PACKAGE_SECTION debug)
set(CPACK_DEBIAN_DBGSYM_PACKAGE_DEPENDS "ugv (= ${PROJECT_VERSION})")
set(CPACK_DEBIAN_DBGSYM_PACKAGE_SHLIBDEPS OFF)
# CPack makes the synopsis of both from CPACK_PACKAGE_DESCRIPTION_SUMMARY; these are the
# extended descriptions.
set(CPACK_COMPONENT_UGV_DESCRIPTION "${CPACK_PACKAGE_DESCRIPTION}")
set(CPACK_COMPONENT_DBGSYM_DESCRIPTION "Debug symbols for the ugv package: the debug information of its programs and\n\
library, found by gdb and systemd-coredump through each file's build-id.")

# conffiles: dpkg asks before replacing an edited /etc/ugv/* file, and purge removes them.
set(conffiles "${UGV_DEBIAN_DIR}/conffiles")
string(REPLACE ";" "\n" conffile_lines "${UGV_CONFFILES}")
file(WRITE ${conffiles} "${conffile_lines}\n")
set(control_extra ${conffiles})
foreach(script postinst prerm postrm)
  configure_file(${CMAKE_SOURCE_DIR}/cmake/debian/${script} ${UGV_DEBIAN_DIR}/${script} COPYONLY)
  list(APPEND control_extra ${UGV_DEBIAN_DIR}/${script})
endforeach()
set(CPACK_DEBIAN_UGV_PACKAGE_CONTROL_EXTRA "${control_extra}")
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION TRUE)
# The tests package what is built; installing must not rebuild the world first.
set(CMAKE_SKIP_INSTALL_ALL_DEPENDENCY TRUE)
include(CPack)
