# VTK's Python wrapping tools (vtkWrapHierarchy, vtkWrapPython, vtkWrapPythonInit) built for
# this machine from VTK's own sources, for a VTK SDK whose tools do not run here (PyPI's
# vtk-sdk 9.5 has macOS programs only). SPT_VTK_WRAPPING_TOOLS_SOURCE names a VTK source tree
# (at least its Wrapping/Tools) of the same version as the SDK: the tools, VTK's
# vtkModuleWrapPython.cmake and the wheel's WrappingPythonCore change together.
#
# The tools are targets of this project, named as VTK names tools built for the host when it
# cross-compiles (VTKCompileTools::WrapPython, ...): vtkModule.cmake and
# vtkModuleWrapPython.cmake then run them in place of the SDK's. The vtkParse library is
# compiled into them (static), so they need the SDK's generated headers only.
set(SPT_VTK_WRAPPING_TOOLS_SOURCE "" CACHE PATH
  "VTK source tree whose Wrapping/Tools are built to wrap the modules (empty: the SDK's tools)")
if (NOT SPT_VTK_WRAPPING_TOOLS_SOURCE)
  return ()
endif ()
get_filename_component(spt_wrapping_tools_dir
  "${SPT_VTK_WRAPPING_TOOLS_SOURCE}/Wrapping/Tools" ABSOLUTE BASE_DIR "${CMAKE_SOURCE_DIR}")
if (NOT EXISTS "${spt_wrapping_tools_dir}/vtkWrapPython.c")
  message(FATAL_ERROR "SPT_VTK_WRAPPING_TOOLS_SOURCE=${SPT_VTK_WRAPPING_TOOLS_SOURCE}: no "
    "${spt_wrapping_tools_dir}/vtkWrapPython.c (a VTK ${VTK_VERSION} source tree is needed, "
    "e.g. `git archive v${VTK_VERSION} Wrapping/Tools` of VTK's repository).")
endif ()
if (TARGET VTKCompileTools::WrapPython)
  message(FATAL_ERROR "SPT_VTK_WRAPPING_TOOLS_SOURCE: VTK already provides host wrapping tools")
endif ()
message(STATUS "SPT: VTK's wrapping tools built from ${spt_wrapping_tools_dir}")

set(spt_parse_sources
  vtkParse.tab.c vtkParseData.c vtkParseDepends.c vtkParseExtras.c vtkParseHierarchy.c
  vtkParseMain.c vtkParseMangle.c vtkParseMerge.c vtkParseMethodType.c vtkParsePreprocess.c
  vtkParseProperties.c vtkParseString.c vtkParseSystem.c vtkWrap.c vtkWrapText.c)
list(TRANSFORM spt_parse_sources PREPEND "${spt_wrapping_tools_dir}/")
add_library(spt_vtk_parse STATIC ${spt_parse_sources})
# The SDK's configured headers (vtkWrappingToolsModule.h, vtkABINamespace.h) after the sources'.
target_include_directories(spt_vtk_parse PUBLIC "${spt_wrapping_tools_dir}"
  "$<TARGET_PROPERTY:VTK::WrappingTools,INTERFACE_INCLUDE_DIRECTORIES>")
set_property(SOURCE "${spt_wrapping_tools_dir}/vtkParseMain.c" APPEND PROPERTY
  COMPILE_DEFINITIONS "VTK_PARSE_VERSION=\"${VTK_VERSION_MAJOR}.${VTK_VERSION_MINOR}\"")
# VTK's code, built as VTK builds it: its warnings are not this project's.
target_compile_options(spt_vtk_parse PRIVATE -w)

# spt_add_wrapping_tool(<VTK's name> <sources...>)
function (spt_add_wrapping_tool name)
  list(TRANSFORM ARGN PREPEND "${spt_wrapping_tools_dir}/")
  add_executable(spt_vtk${name} ${ARGN})
  set_target_properties(spt_vtk${name} PROPERTIES OUTPUT_NAME "vtk${name}"
    RUNTIME_OUTPUT_DIRECTORY "${CMAKE_BINARY_DIR}/wrapping-tools")
  target_compile_options(spt_vtk${name} PRIVATE -w)
  target_link_libraries(spt_vtk${name} PRIVATE spt_vtk_parse)
  add_executable(VTKCompileTools::${name} ALIAS spt_vtk${name})
endfunction ()

spt_add_wrapping_tool(WrapHierarchy vtkWrapHierarchy.c)
spt_add_wrapping_tool(WrapPython
  vtkWrapPython.c vtkWrapPythonClass.c vtkWrapPythonConstant.c vtkWrapPythonEnum.c
  vtkWrapPythonMethod.c vtkWrapPythonMethodDef.c vtkWrapPythonNamespace.c
  vtkWrapPythonNumberProtocol.c vtkWrapPythonOverload.c vtkWrapPythonProperty.c
  vtkWrapPythonTemplate.c vtkWrapPythonType.c)
spt_add_wrapping_tool(WrapPythonInit vtkWrapPythonInit.c)
