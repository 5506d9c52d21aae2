# The tests of the project's modules. Each module keeps its tests in its own Testing/Cxx and
# Testing/Python, which call these functions; the shared test support lives in the top-level
# Testing/ (Cxx/ headers, Python/ helpers, Data/Baseline images, Sanitizers/ suppressions).
set(SPT_TESTING_DIR "${CMAKE_CURRENT_LIST_DIR}/../Testing")
get_filename_component(SPT_TESTING_DIR "${SPT_TESTING_DIR}" ABSOLUTE)

# The real data sets of the Python tests: given at configure time (-DSPT_DATA_DIR=..., by
# default the environment's SPT_DATA_DIR then), or left empty, when each test reads
# SPT_DATA_DIR from the environment ctest runs in. Tests that need a missing data set skip.
set(SPT_DATA_DIR "$ENV{SPT_DATA_DIR}" CACHE PATH
  "The folder of the real data sets the tests read (empty: SPT_DATA_DIR when ctest runs)")

# spt_add_cxx_tests(<driver> TESTS <test>... LIBRARIES <target>... [AUTOINIT <module>...]
#                   [BASELINES <test>=<other test>...])
#
# One driver executable for the tests (as VTK's own tests), one source file and one ctest
# `SPT::<test>` per test, compared with Testing/Data/Baseline/<test>.png where the test
# renders. A test that renders another test's scene names it in BASELINES.
function (spt_add_cxx_tests driver)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "" "TESTS;LIBRARIES;AUTOINIT;BASELINES")
  list(TRANSFORM arg_TESTS APPEND ".cxx" OUTPUT_VARIABLE test_files)
  create_test_sourcelist(test_sources "${driver}.cxx" ${test_files}
    EXTRA_INCLUDE vtkTestDriver.h)
  add_executable("${driver}" ${test_sources})
  target_include_directories("${driver}" PRIVATE "${SPT_TESTING_DIR}/Cxx")
  target_link_libraries("${driver}" PRIVATE ${arg_LIBRARIES} VTK::CommonCore VTK::TestingCore
    VTK::TestingRendering)
  if (arg_AUTOINIT)
    vtk_module_autoinit(TARGETS "${driver}" MODULES ${arg_AUTOINIT})
  endif ()
  set(temporary_dir "${CMAKE_BINARY_DIR}/Testing/Temporary")
  file(MAKE_DIRECTORY "${temporary_dir}")
  foreach (test IN LISTS arg_TESTS)
    set(baseline "${test}")
    foreach (pair IN LISTS arg_BASELINES)
      if (pair MATCHES "^${test}=(.+)$")
        set(baseline "${CMAKE_MATCH_1}")
      endif ()
    endforeach ()
    add_test(NAME "SPT::${test}"
      COMMAND "${driver}" "${test}"
        -T "${temporary_dir}"
        -V "${SPT_TESTING_DIR}/Data/Baseline/${baseline}.png")
    set_tests_properties("SPT::${test}" PROPERTIES SKIP_RETURN_CODE 125)
  endforeach ()
endfunction ()

# spt_add_python_tests()
#
# One ctest `SPT::Python::<name>` per test_<name>.py of the calling directory, run by pytest
# against the package in the build tree, with the shared helpers of Testing/Python on the path
# (pytest puts the test's own directory first, with the helpers of that module's tests only).
# The data sets are found through SPT_DATA_DIR (above); tests that need them are skipped
# without them.
function (spt_add_python_tests)
  set(environment
    "PYTHONPATH=${SPT_PYTHON_BUILD_DIR}:${SPT_TESTING_DIR}/Python"
    "PYTHONDONTWRITEBYTECODE=1"
    "SPT_TEST_ARTIFACTS=${CMAKE_BINARY_DIR}/Testing/Artifacts"
    "SPT_INSTALL_PREFIX=${CMAKE_INSTALL_PREFIX}"
    "SPT_PYTHON_SITE_DIR=${SPT_PYTHON_SITE_DIR}")
  if (SPT_DATA_DIR)
    list(APPEND environment "SPT_DATA_DIR=${SPT_DATA_DIR}")
  endif ()
  # The ParaView plugin tests run ParaView on the plugin of this build tree.
  if (SPT_BUILD_PARAVIEW_PLUGIN)
    list(APPEND environment
      "SPT_PARAVIEW_PLUGIN=${SPT_PARAVIEW_PLUGIN_BUILD_DIR}/SPT/SPT.so"
      "SPT_PARAVIEW_PLUGIN_SUBDIR=${CMAKE_INSTALL_LIBDIR}/${SPT_PARAVIEW_PLUGIN_SUBDIR}")
    if (SPT_EXPAT_COMPAT_LIBRARY)
      list(APPEND environment "SPT_EXPAT_COMPAT_LIBRARY=${SPT_EXPAT_COMPAT_LIBRARY}")
    endif ()
  endif ()
  file(GLOB test_files RELATIVE "${CMAKE_CURRENT_SOURCE_DIR}"
    CONFIGURE_DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/test_*.py")
  foreach (test_file IN LISTS test_files)
    get_filename_component(test_name "${test_file}" NAME_WE)
    add_test(NAME "SPT::Python::${test_name}"
      COMMAND "${SPT_PYTHON_EXECUTABLE}" -m pytest -q -p no:cacheprovider -p spt_pytest_fixtures
              -rs "${CMAKE_CURRENT_SOURCE_DIR}/${test_file}"
      WORKING_DIRECTORY "${CMAKE_SOURCE_DIR}")
    set_tests_properties("SPT::Python::${test_name}" PROPERTIES
      ENVIRONMENT "${environment}"
      SKIP_RETURN_CODE 5)
  endforeach ()
endfunction ()
