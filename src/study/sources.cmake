# pcrf_study: study files, MPI master–worker scheduling, the HDF5 result cube and its
# post-processing. Included by the top-level CMakeLists.txt; adds the `study` and `cube`
# sub-commands to the pcrf executable.

# H5DS (dimension scales, how netCDF-4 stores dimensions) lives in the HDF5 high-level
# library: ask for it on top of the C component the top level found.
find_package(HDF5 REQUIRED COMPONENTS C HL)

add_library(pcrf_study
  src/parallel/result_batch.cpp
  src/parallel/work_queue.cpp
  src/parallel/mpi_session.cpp
  src/parallel/scheduler.cpp
  src/cube/cube_layout.cpp
  src/cube/chunk_grid.cpp
  src/cube/hdf5_util.cpp
  src/cube/cube_writer.cpp
  src/cube/cube_reader.cpp
  src/cube/cube_query.cpp
  src/study/parameters.cpp
  src/study/record_source.cpp
  src/study/toml_fields.cpp
  src/study/study_parser.cpp
  src/study/case_space.cpp
  src/study/case_runner.cpp
  src/study/fingerprint.cpp
  src/study/study_check.cpp
  src/study/study_cube.cpp
  src/study/progress.cpp
  src/study/study_run.cpp
)
# src/ for the private headers (cube/hdf5_util.hpp, parallel/local_channel.hpp, …).
target_include_directories(pcrf_study PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/src)
# Third-party headers are SYSTEM includes: warnings-as-errors applies to our code only.
target_include_directories(pcrf_study SYSTEM PUBLIC ${HDF5_C_INCLUDE_DIRS} ${HDF5_INCLUDE_DIRS})
target_link_libraries(pcrf_study
  PUBLIC pcrf_core MPI::MPI_CXX
  PRIVATE ${HDF5_HL_LIBRARIES} ${HDF5_C_LIBRARIES} tomlplusplus::tomlplusplus)
pcrf_set_warnings(pcrf_study)

set(PCRF_CLI_EXTRA_SOURCES src/cli/study_command.cpp src/cli/cube_command.cpp)
set(PCRF_CLI_EXTRA_LIBS pcrf_study)
add_compile_definitions(PCRF_HAVE_STUDY)
