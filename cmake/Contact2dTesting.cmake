# Contact2dTesting.cmake -- unit-test harness for contact2d (see tests/README.md).
#
# Include after project()/enable_language(Fortran) and enable_testing():
#
#   contact2d_add_pf_test(<pf_file> [LINK_LIBRARIES <lib>...] [LABELS <label>...])
#       Registers one pFUnit test file as one executable and one ctest test,
#       both named after the file stem.  <pf_file> must sit in the calling
#       CMakeLists.txt's directory (pFUnit's add_pfunit_ctest only handles that
#       layout, so the fallback enforces it too) and must contain
#       `module <stem>`.
#         - pFUnit 4 found:  add_pfunit_ctest(<stem> TEST_SOURCES <pf_file>
#                                             LINK_LIBRARIES <lib>...)
#         - otherwise:       tests/pfunit_fallback/funitproc_fallback.py turns
#                            <pf_file> into <stem>.F90 + <stem>_driver.F90 in
#                            the build tree, linked with contact2d_funit.
#
#   contact2d_add_fallback_selftest()
#       Fallback mode only (a no-op with pFUnit): adds the ctest tests
#       funit_selftest_pass, funit_selftest_longest_names,
#       funit_selftest_failures_detected and
#       funit_selftest_preprocessor_rejects (label "selftest").
#
#   contact2d_add_count_selftest()
#       Both backends: adds the ctest test unit_test_count_checked, which runs
#       the first registered unit-test executable again expecting one test
#       more than its .pf holds and must not pass (the count check below is
#       sensitive to the count).
#
# Every test procedure must run: each unit ctest test passes only when the
# runner reports exactly the number of @test lines of its .pf file, all
# passed (pFUnit: "OK (<n> tests)"; fallback: "<stem>: <n> tests, 0 failed").
# pFUnit 4.14 silently drops a test whose @test line carries a comment or
# whose procedure is declared `module subroutine`, `recursive subroutine` or
# with `bind(c)`; the fallback refuses these; the count makes either loud.
#
# Cache options: CONTACT2D_USE_PFUNIT (default ON): set OFF to force the
# fallback even when pFUnit is installed.  CONTACT2D_REQUIRE_PFUNIT (default
# OFF, CI): configure fails when pFUnit is not found instead of falling back.
# After inclusion, CONTACT2D_UNIT_TEST_BACKEND is "pFUnit" or "fallback".
include_guard(GLOBAL)

option(CONTACT2D_USE_PFUNIT "Use an installed pFUnit 4 for unit tests (OFF forces the fallback)" ON)
option(CONTACT2D_REQUIRE_PFUNIT "Fail at configure time when pFUnit 4 is not found, instead of using the fallback" OFF)
if(CONTACT2D_REQUIRE_PFUNIT AND NOT CONTACT2D_USE_PFUNIT)
  message(FATAL_ERROR "CONTACT2D_REQUIRE_PFUNIT=ON contradicts CONTACT2D_USE_PFUNIT=OFF: choose one")
endif()

get_filename_component(_contact2d_fallback_dir "${CMAKE_CURRENT_LIST_DIR}/../tests/pfunit_fallback" ABSOLUTE)
set(_contact2d_funitproc "${_contact2d_fallback_dir}/funitproc_fallback.py")

if(CONTACT2D_USE_PFUNIT)
  find_package(PFUNIT QUIET)
endif()
if(CONTACT2D_REQUIRE_PFUNIT AND NOT PFUNIT_FOUND)
  message(FATAL_ERROR "CONTACT2D_REQUIRE_PFUNIT=ON but pFUnit 4 was not found (the fallback in "
                      "tests/pfunit_fallback is not used with this option). Point CMake at an install: "
                      "-DCMAKE_PREFIX_PATH=<prefix> (or -DPFUNIT_DIR=<prefix>/PFUNIT-4.14/cmake); the prebuilt "
                      "pFUnit 4.14 for Debian 12 unpacks with ../shared/pfunit/install.sh <prefix>")
endif()

if(CONTACT2D_USE_PFUNIT AND PFUNIT_FOUND)
  set(CONTACT2D_UNIT_TEST_BACKEND "pFUnit")
  message(STATUS "contact2d unit tests: using pFUnit ${PFUNIT_VERSION} (add_pfunit_ctest)")
  # The .pf files use no '&'-continued @-directives (pFUnit 4.14 rejects them; the
  # fallback rejects them too), so any pFUnit 4 from 4.14 on builds them.
else()
  set(CONTACT2D_UNIT_TEST_BACKEND "fallback")
  find_package(Python3 COMPONENTS Interpreter REQUIRED)
  message(STATUS "contact2d unit tests: pFUnit not used - project fallback "
                 "(tests/pfunit_fallback, ${Python3_EXECUTABLE})")
  add_library(contact2d_funit STATIC "${_contact2d_fallback_dir}/funit.F90")
  set(_contact2d_funit_moddir "${PROJECT_BINARY_DIR}/mod/contact2d_funit")
  set_target_properties(contact2d_funit PROPERTIES Fortran_MODULE_DIRECTORY "${_contact2d_funit_moddir}")
  target_include_directories(contact2d_funit PUBLIC "${_contact2d_funit_moddir}")
endif()

# Fallback: build executable <name> from <pf_abs>; no ctest test is added.
function(_contact2d_fallback_executable name pf_abs)
  set(gen_dir "${CMAKE_CURRENT_BINARY_DIR}/${name}.funit")
  set(module_f90 "${gen_dir}/${name}.F90")
  set(driver_f90 "${gen_dir}/${name}_driver.F90")
  add_custom_command(
    OUTPUT "${module_f90}" "${driver_f90}"
    COMMAND "${CMAKE_COMMAND}" -E make_directory "${gen_dir}"
    COMMAND "${Python3_EXECUTABLE}" "${_contact2d_funitproc}" "${pf_abs}" "${module_f90}" "${driver_f90}"
    DEPENDS "${pf_abs}" "${_contact2d_funitproc}"
    COMMENT "funitproc_fallback: ${name}.pf"
    VERBATIM)
  add_executable(${name} "${module_f90}" "${driver_f90}")
  set_target_properties(${name} PROPERTIES Fortran_MODULE_DIRECTORY "${gen_dir}/mod")
  target_link_libraries(${name} PRIVATE contact2d_funit ${ARGN})
endfunction()

# <out> = the number of @test lines of <pf_abs> (any line whose first word is @test, so that a
# line pFUnit would skip still counts); the .pf is a configure dependency, so the count follows it.
function(_contact2d_count_tests pf_abs out)
  file(STRINGS "${pf_abs}" lines REGEX "^[ \t]*@[Tt][Ee][Ss][Tt]([^A-Za-z0-9_]|$)")
  list(LENGTH lines n)
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${pf_abs}")
  set(${out} ${n} PARENT_SCOPE)
endfunction()

# <out> = the regular expression a run of <stem> with <n> tests, all passed, prints.
function(_contact2d_count_regex stem n out)
  if(CONTACT2D_UNIT_TEST_BACKEND STREQUAL "pFUnit")
    # pFUnit's summary: " OK" then " (<n> tests)" ("(1 test)") on the next line
    set(${out} "OK[^(]*\\(${n} tests?\\)" PARENT_SCOPE)
  else()
    set(${out} "${stem}: ${n} tests, 0 failed" PARENT_SCOPE)
  endif()
endfunction()

function(contact2d_add_count_selftest)
  get_property(first GLOBAL PROPERTY CONTACT2D_FIRST_PF_TEST)
  if(NOT first)
    return()
  endif()
  list(GET first 0 stem)
  list(GET first 1 n)
  list(GET first 2 dir)
  math(EXPR more "${n} + 1")
  _contact2d_count_regex(${stem} ${more} regex)
  add_test(NAME unit_test_count_checked COMMAND ${stem} WORKING_DIRECTORY "${dir}")
  set_tests_properties(unit_test_count_checked PROPERTIES PASS_REGULAR_EXPRESSION "${regex}" WILL_FAIL TRUE
                       LABELS "unit;selftest")
endfunction()

function(contact2d_add_pf_test pf_file)
  cmake_parse_arguments(PARSE_ARGV 1 _arg "" "" "LINK_LIBRARIES;LABELS")
  if(_arg_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "contact2d_add_pf_test(${pf_file}): unexpected arguments: ${_arg_UNPARSED_ARGUMENTS}")
  endif()
  get_filename_component(pf_abs "${pf_file}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
  get_filename_component(pf_dir "${pf_abs}" DIRECTORY)
  get_filename_component(pf_name "${pf_abs}" NAME)
  get_filename_component(stem "${pf_abs}" NAME_WE)
  if(NOT pf_dir STREQUAL CMAKE_CURRENT_SOURCE_DIR)
    message(FATAL_ERROR "contact2d_add_pf_test(${pf_file}): call it from the CMakeLists.txt in the "
                        "directory holding the .pf file (required by pFUnit's add_pfunit_ctest).")
  endif()
  if(NOT EXISTS "${pf_abs}")
    message(FATAL_ERROR "contact2d_add_pf_test: ${pf_abs} does not exist")
  endif()
  if(TARGET ${stem})
    message(FATAL_ERROR "contact2d_add_pf_test(${pf_file}): target '${stem}' already exists; "
                        ".pf file names must be unique across the project.")
  endif()

  if(CONTACT2D_UNIT_TEST_BACKEND STREQUAL "pFUnit")
    add_pfunit_ctest(${stem} TEST_SOURCES "${pf_name}" LINK_LIBRARIES ${_arg_LINK_LIBRARIES})
  else()
    _contact2d_fallback_executable(${stem} "${pf_abs}" ${_arg_LINK_LIBRARIES})
    add_test(NAME ${stem} COMMAND ${stem} WORKING_DIRECTORY "${CMAKE_CURRENT_BINARY_DIR}")
  endif()
  # every test procedure ran and passed: the runner's count = the .pf's @test lines
  _contact2d_count_tests("${pf_abs}" ntests)
  _contact2d_count_regex(${stem} ${ntests} regex)
  set_tests_properties(${stem} PROPERTIES PASS_REGULAR_EXPRESSION "${regex}")
  get_property(first GLOBAL PROPERTY CONTACT2D_FIRST_PF_TEST)
  if(NOT first)
    set_property(GLOBAL PROPERTY CONTACT2D_FIRST_PF_TEST "${stem};${ntests};${CMAKE_CURRENT_BINARY_DIR}")
  endif()
  if(_arg_LABELS)
    set_tests_properties(${stem} PROPERTIES LABELS "${_arg_LABELS}")
  endif()
endfunction()

function(contact2d_add_fallback_selftest)
  if(NOT CONTACT2D_UNIT_TEST_BACKEND STREQUAL "fallback")
    return()
  endif()
  set(dir "${_contact2d_fallback_dir}/selftest")
  _contact2d_fallback_executable(funit_selftest_pass "${dir}/funit_selftest_pass.pf")
  _contact2d_fallback_executable(funit_selftest_fail "${dir}/funit_selftest_fail.pf")
  add_test(NAME funit_selftest_pass COMMAND funit_selftest_pass)
  # the longest names pFUnit 4.14 builds (57-character module, 63-character procedure)
  set(longest funit_selftest_module_name_of_57_characters_pfunit_builds)
  _contact2d_fallback_executable(${longest} "${dir}/${longest}.pf")
  add_test(NAME funit_selftest_longest_names COMMAND ${longest})
  foreach(pair "funit_selftest_pass;funit_selftest_pass" "funit_selftest_longest_names;${longest}")
    list(GET pair 0 test)
    list(GET pair 1 name)
    _contact2d_count_tests("${dir}/${name}.pf" ntests)
    _contact2d_count_regex(${name} ${ntests} regex)
    set_tests_properties(${test} PROPERTIES PASS_REGULAR_EXPRESSION "${regex}")
  endforeach()
  # The failing executable is deliberately not a test of its own: the check
  # script runs it and inverts the verdict only if every failure is reported.
  add_test(NAME funit_selftest_failures_detected
    COMMAND "${Python3_EXECUTABLE}" "${dir}/check_selftest.py" failures
            "$<TARGET_FILE:funit_selftest_fail>" "${dir}/funit_selftest_fail.pf")
  add_test(NAME funit_selftest_preprocessor_rejects
    COMMAND "${Python3_EXECUTABLE}" "${dir}/check_selftest.py" rejects "${_contact2d_funitproc}")
  set_tests_properties(funit_selftest_pass funit_selftest_longest_names funit_selftest_failures_detected
    funit_selftest_preprocessor_rejects PROPERTIES LABELS "selftest")
endfunction()
