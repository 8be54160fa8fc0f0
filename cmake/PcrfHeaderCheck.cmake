# Every public header compiles alone, with nothing on its include path but what its own
# library links: one translation unit per header, generated at configure time, in an object
# library per library that links only that library. A header that leans on something its
# library does not link (or on an include it forgot) fails to compile.
#   pcrf_header_check(TARGET LIBRARY...): the target that builds them all (not part of `all`).
function(pcrf_header_check target)
  set(objects)
  foreach(lib IN LISTS ARGN)
    file(GLOB headers CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/${lib}/include/pcrf/${lib}/*.hpp)
    set(sources)
    foreach(header IN LISTS headers)
      get_filename_component(name ${header} NAME)
      set(source ${PROJECT_BINARY_DIR}/header_check/${lib}/${name}.cpp)
      # Twice: the second inclusion checks the include guard.
      file(CONFIGURE OUTPUT ${source} CONTENT "#include \"pcrf/${lib}/${name}\"\n#include \"pcrf/${lib}/${name}\"\n" @ONLY)
      list(APPEND sources ${source})
    endforeach()
    add_library(${target}_${lib} OBJECT EXCLUDE_FROM_ALL ${sources})
    target_link_libraries(${target}_${lib} PRIVATE pcrf_${lib})
    pcrf_set_warnings(${target}_${lib})
    list(APPEND objects ${target}_${lib})
  endforeach()
  # The headers every library shares, with pcrf_headers alone.
  file(GLOB headers CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/include/pcrf/*.hpp)
  set(sources)
  foreach(header IN LISTS headers)
    get_filename_component(name ${header} NAME)
    set(source ${PROJECT_BINARY_DIR}/header_check/shared/${name}.cpp)
    file(CONFIGURE OUTPUT ${source} CONTENT "#include \"pcrf/${name}\"\n#include \"pcrf/${name}\"\n" @ONLY)
    list(APPEND sources ${source})
  endforeach()
  add_library(${target}_shared OBJECT EXCLUDE_FROM_ALL ${sources})
  target_link_libraries(${target}_shared PRIVATE pcrf_headers)
  pcrf_set_warnings(${target}_shared)
  add_custom_target(${target} DEPENDS ${objects} ${target}_shared)
endfunction()
