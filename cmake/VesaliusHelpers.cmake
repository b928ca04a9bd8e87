# Helpers that keep each module's CMakeLists.txt to a few lines.

# Flags for every target of ours: warnings, and the sanitizers when asked.
function(vesalius_target_flags target)
  target_compile_options(${target} PRIVATE -Wall -Wextra)
  if(VESALIUS_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
  if(VESALIUS_SANITIZE)
    target_compile_options(${target} PRIVATE -fsanitize=address,undefined -fno-omit-frame-pointer
                                             -fno-sanitize-recover=undefined)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
endfunction()

# vesalius_module(NAME <m> SOURCES ... [PUBLIC_LIBS ...] [PRIVATE_LIBS ...])
# Creates library vesalius_<m> with alias vesalius::<m>; headers live in include/vesalius/<m>/.
function(vesalius_module)
  cmake_parse_arguments(M "" "NAME" "SOURCES;PUBLIC_LIBS;PRIVATE_LIBS" ${ARGN})
  add_library(vesalius_${M_NAME} ${M_SOURCES})
  add_library(vesalius::${M_NAME} ALIAS vesalius_${M_NAME})
  target_include_directories(vesalius_${M_NAME} PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include)
  target_link_libraries(vesalius_${M_NAME} PUBLIC ${M_PUBLIC_LIBS} PRIVATE ${M_PRIVATE_LIBS})
  set_target_properties(vesalius_${M_NAME} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  vesalius_target_flags(vesalius_${M_NAME})
  install(TARGETS vesalius_${M_NAME} LIBRARY DESTINATION ${VESALIUS_LIB_INSTALL_DIR}
                                     ARCHIVE DESTINATION ${VESALIUS_LIB_INSTALL_DIR})
endfunction()

# Every test compiles with one precompiled header: GoogleTest, Eigen and the standard library parsed once
# rather than in each of the tests' 200-odd translation units (a sixth of their compile time).
function(vesalius_test_pch)
  if(TARGET vesalius_test_pch)
    return()
  endif()
  add_library(vesalius_test_pch OBJECT ${PROJECT_SOURCE_DIR}/tests/support/test_pch.cpp)
  target_link_libraries(vesalius_test_pch PRIVATE GTest::gtest Eigen3::Eigen)
  target_precompile_headers(vesalius_test_pch PRIVATE <gtest/gtest.h> <Eigen/Dense> <Eigen/Sparse>
                            <algorithm> <filesystem> <fstream> <iostream> <map> <string> <vector>)
  vesalius_target_flags(vesalius_test_pch)
endfunction()

# vesalius_test(NAME <t> SOURCES ... LIBS ... LABELS ... [LONG])
# A GoogleTest executable whose tests ctest discovers, each carrying LABELS. Tests find the shipped
# data through the VESALIUS_TESTDATA macro and may write under VESALIUS_TEST_OUTPUT. LONG: some of its
# tests take minutes, and ctest starts them all first (COST): on a fresh clone ctest has no timings of its
# own and starts tests in the order they were declared, which leaves the last long one running alone at
# the end of `ctest -j`.
function(vesalius_test)
  cmake_parse_arguments(T "LONG" "NAME" "SOURCES;LIBS;LABELS" ${ARGN})
  add_executable(${T_NAME} ${T_SOURCES})
  target_link_libraries(${T_NAME} PRIVATE ${T_LIBS} GTest::gtest GTest::gtest_main)
  vesalius_test_pch()
  target_precompile_headers(${T_NAME} REUSE_FROM vesalius_test_pch)
  target_include_directories(${T_NAME} PRIVATE ${PROJECT_SOURCE_DIR}/tests/support)
  target_compile_definitions(${T_NAME} PRIVATE
    VESALIUS_TESTDATA="${PROJECT_SOURCE_DIR}/testdata"
    VESALIUS_TEST_OUTPUT="${PROJECT_BINARY_DIR}/test-output/${T_NAME}")
  vesalius_target_flags(${T_NAME})
  set(environment "")
  if(VESALIUS_SANITIZE AND "gui" IN_LIST T_LABELS)
    # Mesa's GL driver, loaded by dlopen under Xvfb, leaks a few hundred bytes and is unloaded before
    # LeakSanitizer reports, so the leak cannot be attributed or suppressed by name. GUI tests keep
    # ASan and UBSan but not the leak check.
    set(environment ENVIRONMENT ASAN_OPTIONS=detect_leaks=0)
  endif()
  gtest_discover_tests(${T_NAME} NO_PRETTY_VALUES PROPERTIES LABELS "${T_LABELS}" ${environment}
                       DISCOVERY_TIMEOUT 60)
  if(T_LONG)
    # Read by ctest after the discovered tests, whose names are in ${T_NAME}_TESTS.
    set(cost ${CMAKE_CURRENT_BINARY_DIR}/${T_NAME}_cost.cmake)
    file(WRITE ${cost} "if(${T_NAME}_TESTS)\n  set_tests_properties(\${${T_NAME}_TESTS} PROPERTIES COST 1000)\nendif()\n")
    set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES ${cost})
  endif()
endfunction()
