// The case kernel on a CUDA device (kernel_launch.hpp): one thread per case over the same
// source as the host build (case_kernel.hpp), compiled with --fmad=false (no fused
// multiply-add the CPU path does not have). The record is copied once per group to global
// memory and read through the read-only data path (case_kernel.hpp's load_sample: __ldg), as
// are the prestressed frames' tables.
#include <cuda_runtime.h>

#include <string>

#include "kernel_launch.hpp"

namespace pcrf::device {
namespace {

__global__ void solve_cases_kernel(const KernelCase* __restrict__ cases, std::size_t count, KernelRecord record,
                                   KernelTables tables, KernelResult* __restrict__ results) {
  const std::size_t i = static_cast<std::size_t>(blockIdx.x) * blockDim.x + threadIdx.x;
  if (i >= count) return;
  const KernelCase c = cases[i];  // the case's numbers in registers
  KernelResult r;
  solve_kernel_case(c, record, tables, r);
  results[i] = r;
}

/// False with `error` naming the call when `status` is a failure.
bool ok(cudaError_t status, const char* call, std::string& error) {
  if (status == cudaSuccess) return true;
  error = std::string(call) + ": " + cudaGetErrorString(status);
  return false;
}

/// Device memory freed on every path.
template <class T>
struct DeviceArray {
  T* p = nullptr;
  ~DeviceArray() {
    if (p != nullptr) cudaFree(p);
  }
  bool allocate(std::size_t n, std::string& error) {
    return ok(cudaMalloc(reinterpret_cast<void**>(&p), n * sizeof(T)), "cudaMalloc", error);
  }
};

constexpr int kThreadsPerBlock = 128;

}  // namespace

std::string cuda_device_problem(std::string& name) {
  int count = 0;
  const cudaError_t status = cudaGetDeviceCount(&count);
  if (status != cudaSuccess) return std::string("no usable CUDA device: ") + cudaGetErrorString(status);
  if (count < 1) return "no CUDA device on this machine";
  cudaDeviceProp prop{};
  if (cudaGetDeviceProperties(&prop, 0) != cudaSuccess) return "CUDA device 0: its properties cannot be read";
  name = prop.name;
  if (cudaSetDevice(0) != cudaSuccess || cudaFree(nullptr) != cudaSuccess)
    return "CUDA device 0 (" + name + "): no context can be made on it";
  return {};
}

bool cuda_solve_cases(const KernelCase* cases, std::size_t count, const KernelRecord& record,
                      const KernelTableStore& tables, KernelResult* results, std::string& error) {
  if (count == 0) return true;
  DeviceArray<KernelCase> d_cases;
  DeviceArray<KernelResult> d_results;
  DeviceArray<double> d_samples, d_coefficients;
  DeviceArray<unsigned char> d_tabulated;
  // One element at least: a group of rigid rockers has no table.
  if (!d_cases.allocate(count, error) || !d_results.allocate(count, error) || !d_samples.allocate(record.count, error) ||
      !d_coefficients.allocate(tables.coefficients.size() + 1, error) ||
      !d_tabulated.allocate(tables.tabulated.size() + 1, error))
    return false;
  if (!ok(cudaMemcpy(d_cases.p, cases, count * sizeof(KernelCase), cudaMemcpyHostToDevice), "cudaMemcpy cases", error) ||
      !ok(cudaMemcpy(d_samples.p, record.samples_m_s2, record.count * sizeof(double), cudaMemcpyHostToDevice),
          "cudaMemcpy record", error) ||
      !ok(cudaMemcpy(d_coefficients.p, tables.coefficients.data(), tables.coefficients.size() * sizeof(double),
                     cudaMemcpyHostToDevice),
          "cudaMemcpy tables", error) ||
      !ok(cudaMemcpy(d_tabulated.p, tables.tabulated.data(), tables.tabulated.size(), cudaMemcpyHostToDevice),
          "cudaMemcpy tables", error))
    return false;
  KernelRecord on_device = record;
  on_device.samples_m_s2 = d_samples.p;
  const auto blocks = static_cast<unsigned>((count + kThreadsPerBlock - 1) / kThreadsPerBlock);
  const KernelTables tables_on_device{d_coefficients.p, d_tabulated.p};
  solve_cases_kernel<<<blocks, kThreadsPerBlock>>>(d_cases.p, count, on_device, tables_on_device, d_results.p);
  if (!ok(cudaGetLastError(), "kernel launch", error) || !ok(cudaDeviceSynchronize(), "kernel run", error)) return false;
  return ok(cudaMemcpy(results, d_results.p, count * sizeof(KernelResult), cudaMemcpyDeviceToHost), "cudaMemcpy results",
            error);
}

}  // namespace pcrf::device
