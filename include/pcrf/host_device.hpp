/// \file host_device.hpp
/// \brief PCRF_HD: marks a function that the case kernel (src/solver/device/) runs on both
/// sides — `__host__ __device__` where nvcc compiles it, nothing in a host build. Only
/// functions without exceptions, heap, std::function or virtual calls carry it.
#pragma once

#if defined(__CUDACC__)
#define PCRF_HD __host__ __device__
#else
#define PCRF_HD
#endif
