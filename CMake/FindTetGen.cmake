# FindTetGen: TetGen 1.5 built as a library (Debian: libtet1.5-dev, header tetgen.h, libtet).
#
# Defines TetGen_FOUND, TetGen_INCLUDE_DIR, TetGen_LIBRARY and the imported target
# TetGen::TetGen. The target carries TETLIBRARY: the library is built with it, and tetgen.h's
# inline terminatetetgen() must throw (as the library's copy does) instead of calling exit().
find_path(TetGen_INCLUDE_DIR NAMES tetgen.h)
find_library(TetGen_LIBRARY NAMES tet tetgen)

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(TetGen
  REQUIRED_VARS TetGen_LIBRARY TetGen_INCLUDE_DIR)
mark_as_advanced(TetGen_INCLUDE_DIR TetGen_LIBRARY)

if (TetGen_FOUND AND NOT TARGET TetGen::TetGen)
  add_library(TetGen::TetGen UNKNOWN IMPORTED)
  set_target_properties(TetGen::TetGen PROPERTIES
    IMPORTED_LOCATION "${TetGen_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${TetGen_INCLUDE_DIR}"
    INTERFACE_COMPILE_DEFINITIONS "TETLIBRARY")
endif ()
