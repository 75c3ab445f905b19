# Precompiled headers for the tests: about ninety one-file programs that each
# parse GoogleTest (and, end to end, gRPC and the messages) again. Each group
# compiled alike shares one header build (a test of its own each would not pay
# it back): 100 s less compiling in a Release build, more with the
# sanitizers. Tried on the CLI's and scallopd's own files too, and dropped:
# GCC loads a 270 MB header image in every file, which cost the light files
# (options, output, analysis) more than it saved the heavy ones.
# Only library and standard headers go in, so that editing our own headers
# rebuilds no more than before.
option(SCALLOP_PRECOMPILED_HEADERS "Precompile the tests' library headers" ON)

# NAME: an object library compiled as the programs that link exactly the
# libraries LINKING are, holding the precompiled HEADERS that those programs
# reuse (scallop_reuse_headers). A program linking more may be compiled with
# other definitions, which GCC refuses (-Winvalid-pch): give it none.
function(scallop_shared_headers name)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "" "LINKING;HEADERS")
  if(NOT SCALLOP_PRECOMPILED_HEADERS)
    return()
  endif()
  set(anchor ${CMAKE_CURRENT_BINARY_DIR}/${name}.cc)
  if(NOT EXISTS ${anchor})
    file(WRITE ${anchor} "// Compiled only to hold the precompiled headers of ${name}.\n")
  endif()
  add_library(${name} OBJECT ${anchor})
  target_link_libraries(${name} PRIVATE ${arg_LINKING})
  target_precompile_headers(${name} PRIVATE ${arg_HEADERS})
endfunction()

# TARGET uses the precompiled headers of FROM (made by scallop_shared_headers),
# when they are built.
function(scallop_reuse_headers target from)
  if(SCALLOP_PRECOMPILED_HEADERS)
    target_precompile_headers(${target} REUSE_FROM ${from})
  endif()
endfunction()
