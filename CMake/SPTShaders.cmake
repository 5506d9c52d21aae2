# spt_encode_shaders(<module library name> <sources variable> <headers variable> [EXPORTED]
#                    <files>...)
#
# Embeds each GLSL file as a C string (vtk_encode_string) in the module whose library name is
# given (SPTRenderingCore: header SPTRenderingCoreModule.h): the shaders are compiled into the
# library, never read from disk. They are private to it (SPTRENDERINGCORE_NO_EXPORT), or, with
# EXPORTED, reachable from the other modules' shader code (SPTRENDERINGCORE_EXPORT).
function (spt_encode_shaders library sources_var headers_var)
  cmake_parse_arguments(PARSE_ARGV 3 arg "EXPORTED" "" "")
  string(TOUPPER "${library}" upper)
  set(symbol "${upper}_NO_EXPORT")
  if (arg_EXPORTED)
    set(symbol "${upper}_EXPORT")
  endif ()
  set(sources)
  set(headers)
  foreach (shader_file IN LISTS arg_UNPARSED_ARGUMENTS)
    vtk_encode_string(
      INPUT         "${shader_file}"
      EXPORT_SYMBOL "${symbol}"
      EXPORT_HEADER "${library}Module.h"
      HEADER_OUTPUT header
      SOURCE_OUTPUT source)
    list(APPEND sources "${source}")
    list(APPEND headers "${header}")
  endforeach ()
  set("${sources_var}" "${sources}" PARENT_SCOPE)
  set("${headers_var}" "${headers}" PARENT_SCOPE)
endfunction ()
