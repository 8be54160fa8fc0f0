# SLEEF (libsleef-dev): the rigid rockers' sin/cos. Where found, the one-case solver takes
# SLEEF's deterministic scalar sincos (the cinz family: no fused multiply-add, the same bits
# on every CPU) and the batch kernels the same family's vector functions, so a lane gives the
# one-case answer bit for bit with a vectorised sin/cos (docs/batches.md). Without it both take
# the C library's. One switch for both: the target pcrf_sleef, linked by pcrf_model and
# pcrf_solver, carries PCRF_HAVE_SLEEF.
option(PCRF_USE_SLEEF "Take the rigid rockers' sin/cos from SLEEF where libsleef-dev is found" ON)
add_library(pcrf_sleef INTERFACE)
if(PCRF_USE_SLEEF)
  find_library(SLEEF_LIBRARY sleef)
  find_path(SLEEF_INCLUDE_DIR sleef.h)
endif()
if(PCRF_USE_SLEEF AND SLEEF_LIBRARY AND SLEEF_INCLUDE_DIR)
  target_compile_definitions(pcrf_sleef INTERFACE PCRF_HAVE_SLEEF)
  target_include_directories(pcrf_sleef SYSTEM INTERFACE ${SLEEF_INCLUDE_DIR})
  target_link_libraries(pcrf_sleef INTERFACE ${SLEEF_LIBRARY})
  message(STATUS "rigid rockers' sin/cos: SLEEF, deterministic family (${SLEEF_LIBRARY})")
else()
  message(STATUS "rigid rockers' sin/cos: the C library's (SLEEF not used: apt-get install libsleef-dev)")
endif()
