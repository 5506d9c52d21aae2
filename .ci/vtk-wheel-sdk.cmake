# The options of PyPI's Linux vtk wheel (VTK's .gitlab/ci/configure_wheel.cmake, with its
# configure_common.cmake and configure_options.cmake for CMAKE_CONFIGURATION
# wheel_linux311_x86_64), for an SDK made from VTK's source by .ci/vtk-source-sdk. Only the
# modules this project uses (and what they depend on) are enabled: the SDK configures them and
# generates their headers, but builds no library, whose place the wheel's libraries take.
set(VTK_WHEEL_BUILD ON CACHE BOOL "")
set(VTK_INSTALL_SDK ON CACHE BOOL "")
set(Python3_FIND_STRATEGY LOCATION CACHE STRING "")
set(VTK_ENABLE_REMOTE_MODULES OFF CACHE BOOL "")
set(VTK_DEBUG_LEAKS OFF CACHE BOOL "")
set(VTK_USE_PCH OFF CACHE BOOL "")
set(VTK_DISPATCH_SOA_ARRAYS ON CACHE BOOL "")
set(VTK_WRAP_SERIALIZATION ON CACHE BOOL "")
set(VTK_RELOCATABLE_INSTALL ON CACHE BOOL "")
set(VTK_ENABLE_CATALYST OFF CACHE BOOL "")
set(VTK_BUILD_DOCUMENTATION OFF CACHE BOOL "")
set(VTK_ENABLE_KITS OFF CACHE BOOL "")
set(VTK_USE_MPI OFF CACHE BOOL "")
set(VTK_DEFAULT_RENDER_WINDOW_OFFSCREEN OFF CACHE BOOL "")
set(VTK_ENABLE_WEBGPU OFF CACHE BOOL "")
set(VTK_USE_CUDA OFF CACHE BOOL "")
set(VTK_WRAP_JAVA OFF CACHE BOOL "")
set(VTK_SMP_IMPLEMENTATION_TYPE Sequential CACHE STRING "")
set(VTK_ENABLE_VISKORES_OVERRIDES OFF CACHE BOOL "")
set(CMAKE_BUILD_TYPE Release CACHE STRING "")
set(VTK_BUILD_ALL_MODULES OFF CACHE BOOL "")
set(VTK_BUILD_EXAMPLES OFF CACHE BOOL "")
foreach (group IN ITEMS Imaging MPI Qt Rendering StandAlone Views Web)
  set(VTK_GROUP_ENABLE_${group} DONT_WANT CACHE STRING "")
endforeach ()
foreach (module IN ITEMS CommonCore CommonDataModel CommonExecutionModel CommonMath
    CommonSystem FiltersCore FiltersGeneral FiltersSources IOLegacy InteractionStyle
    ParallelCore RenderingCore RenderingOpenGL2 RenderingVolume RenderingVolumeOpenGL2
    TestingCore TestingRendering WrappingPythonCore)
  set(VTK_MODULE_ENABLE_VTK_${module} YES CACHE STRING "")
endforeach ()
