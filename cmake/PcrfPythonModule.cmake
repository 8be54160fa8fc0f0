# The Python module `import pcrf` (src/python): built where the Python development headers and
# pybind11 are found (Debian: python3-dev pybind11-dev), for the Python that draws the figures
# (PCRF_PYTHON, the system python3 where it has matplotlib; -DPython_EXECUTABLE=… overrides).
# Where they are not, configuring says so and the rest builds as before.
set(PCRF_PYTHON_MODULE OFF)
if(NOT Python_EXECUTABLE AND IS_ABSOLUTE "${PCRF_PYTHON}")
  set(Python_EXECUTABLE "${PCRF_PYTHON}")
endif()
find_package(Python 3.9 COMPONENTS Interpreter Development.Module)
if(Python_FOUND)
  set(PYBIND11_FINDPYTHON ON)
  find_package(pybind11 2.6 CONFIG QUIET)
endif()
if(Python_FOUND AND pybind11_FOUND)
  set(PCRF_PYTHON_MODULE ON)
  # The module is a shared object: the static libraries it links must be position-independent.
  set(CMAKE_POSITION_INDEPENDENT_CODE ON)
  message(STATUS "Python module pcrf: built for ${Python_EXECUTABLE} (use it with PYTHONPATH=build/python)")
elseif(NOT Python_FOUND)
  message(STATUS "Python module pcrf: NOT built: no Python development headers (apt-get install python3-dev pybind11-dev)")
else()
  message(STATUS "Python module pcrf: NOT built: pybind11 not found (apt-get install pybind11-dev)")
endif()
