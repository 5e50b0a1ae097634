# Compiler warnings every target of ours gets.
add_library(ugv_warnings INTERFACE)
target_compile_options(ugv_warnings INTERFACE
  $<$<COMPILE_LANGUAGE:CXX>:-Wall -Wextra -Wconversion -Wshadow -Wno-sign-conversion>
  $<$<BOOL:${UGV_WERROR}>:-Werror>)
# Every program prints this with --version.
target_compile_definitions(ugv_warnings INTERFACE UGV_VERSION="${PROJECT_VERSION}")
if(UGV_SANITIZE)
  target_compile_options(ugv_warnings INTERFACE -fsanitize=address,undefined -fno-omit-frame-pointer
                                                -fno-sanitize-recover=undefined)
  target_link_options(ugv_warnings INTERFACE -fsanitize=address,undefined)
endif()

# One Catch2 (v2) main shared by every test executable.
add_library(ugv_catch_main STATIC ${CMAKE_SOURCE_DIR}/tests/catch_main.cpp)
target_link_libraries(ugv_catch_main PUBLIC Catch2::Catch2)
target_include_directories(ugv_catch_main PUBLIC ${CMAKE_SOURCE_DIR}/tests/support)

# ugv_add_test(NAME name SOURCES a.cpp ... LIBS lib ... [LABELS l ...] [TIMEOUT s]
#              [SKIP_RETURN_CODE c] [RUN_SERIAL])
# One CTest entry per test executable. A test that cannot run on this machine exits with its
# SKIP_RETURN_CODE (77 by convention) and CTest reports it as skipped, by name.
function(ugv_add_test)
  cmake_parse_arguments(T "RUN_SERIAL" "NAME;TIMEOUT;SKIP_RETURN_CODE" "SOURCES;LIBS;LABELS" ${ARGN})
  add_executable(${T_NAME} ${T_SOURCES})
  target_link_libraries(${T_NAME} PRIVATE ugv_catch_main ugv_warnings ${T_LIBS})
  target_compile_definitions(${T_NAME} PRIVATE
    UGV_SOURCE_DIR="${CMAKE_SOURCE_DIR}" UGV_BINARY_DIR="${CMAKE_BINARY_DIR}"
    UGV_SHARED_DIR="${CMAKE_SOURCE_DIR}/../shared")
  add_test(NAME ${T_NAME} COMMAND ${T_NAME})
  if(NOT T_TIMEOUT)
    set(T_TIMEOUT 120)
  endif()
  set_tests_properties(${T_NAME} PROPERTIES TIMEOUT ${T_TIMEOUT}
    ENVIRONMENT "UGV_BIN_DIR=${CMAKE_BINARY_DIR}/bin;UGV_SOURCE_DIR=${CMAKE_SOURCE_DIR}")
  if(T_LABELS)
    set_tests_properties(${T_NAME} PROPERTIES LABELS "${T_LABELS}")
  endif()
  if(T_SKIP_RETURN_CODE)
    set_tests_properties(${T_NAME} PROPERTIES SKIP_RETURN_CODE ${T_SKIP_RETURN_CODE})
  endif()
  if(T_RUN_SERIAL)
    set_tests_properties(${T_NAME} PROPERTIES RUN_SERIAL TRUE)
  endif()
endfunction()

# ugv_add_program(NAME ugv-xyz SOURCES main.cpp ... LIBS ...): an installed program in bin/.
function(ugv_add_program)
  cmake_parse_arguments(P "" "NAME" "SOURCES;LIBS" ${ARGN})
  add_executable(${P_NAME} ${P_SOURCES})
  target_link_libraries(${P_NAME} PRIVATE ugv_warnings ${P_LIBS})
  set_target_properties(${P_NAME} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/bin)
  install(TARGETS ${P_NAME} RUNTIME DESTINATION bin)
  set_property(GLOBAL APPEND PROPERTY UGV_PACKAGED_ELF ${P_NAME})   # its symbols go to ugv-dbgsym
endfunction()

# ugv_add_library(NAME ugv_xyz SOURCES ... [PUBLIC_LIBS ...] [PRIVATE_LIBS ...])
# A static library whose public headers live in <folder>/include.
function(ugv_add_library)
  cmake_parse_arguments(L "" "NAME" "SOURCES;PUBLIC_LIBS;PRIVATE_LIBS" ${ARGN})
  add_library(${L_NAME} STATIC ${L_SOURCES})
  target_include_directories(${L_NAME} PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include)
  target_link_libraries(${L_NAME} PUBLIC ${L_PUBLIC_LIBS} PRIVATE ugv_warnings ${L_PRIVATE_LIBS})
  set_target_properties(${L_NAME} PROPERTIES POSITION_INDEPENDENT_CODE ON)
endfunction()

# ugv_add_benchmark(NAME name SOURCES ... LIBS ...): a Google Benchmark program in bin/perf.
function(ugv_add_benchmark)
  cmake_parse_arguments(B "" "NAME" "SOURCES;LIBS" ${ARGN})
  if(NOT UGV_BUILD_PERF OR NOT benchmark_FOUND)
    return()
  endif()
  add_executable(${B_NAME} ${B_SOURCES})
  target_link_libraries(${B_NAME} PRIVATE benchmark::benchmark_main ugv_warnings ${B_LIBS})
  set_target_properties(${B_NAME} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/bin/perf)
endfunction()

# ugv_add_fuzzer(NAME fuzz_x SOURCES ... LIBS ... [SEEDS dir-or-file ...])
# A libFuzzer target, built only in the fuzz tree (tools/fuzz: clang, UGV_FUZZ=ON, the whole
# tree compiled with -fsanitize=fuzzer-no-link,address,undefined). SEEDS are copied into the
# target's corpus before each run.
function(ugv_add_fuzzer)
  cmake_parse_arguments(F "" "NAME" "SOURCES;LIBS;SEEDS" ${ARGN})
  if(NOT UGV_FUZZ)
    return()
  endif()
  add_executable(${F_NAME} ${F_SOURCES})
  target_link_libraries(${F_NAME} PRIVATE ugv_warnings ${F_LIBS})
  target_link_options(${F_NAME} PRIVATE -fsanitize=fuzzer)
  set_target_properties(${F_NAME} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/fuzz)
  string(REPLACE ";" "\n" seeds "${F_SEEDS}")
  file(WRITE ${CMAKE_BINARY_DIR}/fuzz/${F_NAME}.seeds "${seeds}\n")
  if(NOT TARGET fuzz_all)
    add_custom_target(fuzz_all)
  endif()
  add_dependencies(fuzz_all ${F_NAME})
endfunction()

# ugv_add_daemon(NAME xyz [SOURCES more.cpp ...] LIBS ...)
# A daemon made from the template (docs/ARCHITECTURE.md): daemons/xyz/ holds main.cpp and
# xyz_config, xyz_node and xyz_messages (.hpp and .cpp). Everything but main.cpp is the
# library ugv_xyz_node, which the daemon's tests and benchmarks link; ugv-xyz is main.cpp.
function(ugv_add_daemon)
  cmake_parse_arguments(D "" "NAME" "SOURCES;LIBS" ${ARGN})
  set(parts main.cpp)
  foreach(part config node messages)
    list(APPEND parts ${D_NAME}_${part}.hpp ${D_NAME}_${part}.cpp)
  endforeach()
  foreach(file ${parts})
    if(NOT EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/${file})
      message(FATAL_ERROR "daemons/${D_NAME}: ${file} is missing (the daemon template, docs/ARCHITECTURE.md)")
    endif()
  endforeach()
  add_library(ugv_${D_NAME}_node STATIC
    ${D_NAME}_config.cpp ${D_NAME}_node.cpp ${D_NAME}_messages.cpp ${D_SOURCES})
  target_include_directories(ugv_${D_NAME}_node PUBLIC ${CMAKE_CURRENT_SOURCE_DIR})
  target_link_libraries(ugv_${D_NAME}_node PUBLIC ugv_daemon ugv_lcmtypes ${D_LIBS} PRIVATE ugv_warnings)
  ugv_add_program(NAME ugv-${D_NAME} SOURCES main.cpp LIBS ugv_${D_NAME}_node)
endfunction()
