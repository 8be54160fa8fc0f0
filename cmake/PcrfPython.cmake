# PCRF_PYTHON: the Python that draws pcrf's figures (`pcrf plot`), the first python3 that
# imports matplotlib and numpy. A pyenv or venv python3 first on PATH often lacks Debian's
# python3-matplotlib, so /usr/bin/python3 is tried too. Override: -DPCRF_PYTHON=… at
# configure time, or the PCRF_PYTHON environment variable at run time.
if(NOT PCRF_PYTHON)
  find_program(PCRF_PYTHON_ON_PATH NAMES python3)
  foreach(candidate IN ITEMS ${PCRF_PYTHON_ON_PATH} /usr/bin/python3)
    if(EXISTS "${candidate}")
      execute_process(COMMAND "${candidate}" -c "import matplotlib, numpy"
                      RESULT_VARIABLE has_matplotlib OUTPUT_QUIET ERROR_QUIET)
      if(has_matplotlib EQUAL 0)
        set(PCRF_PYTHON "${candidate}" CACHE FILEPATH "Python with matplotlib, for pcrf plot")
        break()
      endif()
    endif()
  endforeach()
  if(NOT PCRF_PYTHON)
    message(STATUS "pcrf plot: no python3 with matplotlib found (apt-get install python3-matplotlib)")
    set(PCRF_PYTHON python3)
  endif()
endif()
message(STATUS "pcrf plot draws with ${PCRF_PYTHON}")
