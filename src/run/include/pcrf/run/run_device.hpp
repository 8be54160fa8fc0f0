/// \file run_device.hpp
/// \brief Where a run's cases are solved ([run] device, docs/gpu.md): the CPU engine, or the
/// case kernel on a CUDA device behind the group-of-cases interface (case_group.hpp). A GPU
/// rank is handed large groups of one excitation; its answers go into the cube as any
/// other rank's.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <memory>

#include "pcrf/run/study_run.hpp"
#include "pcrf/solver/case_group.hpp"
#include "pcrf/study/study.hpp"
#include "pcrf/user_error.hpp"

namespace pcrf::run {

/// Cases of one excitation a GPU rank is handed and solves in one launch (≥ 10⁴: a kernel
/// of one case per thread fills an H100's 132 multiprocessors at the occupancy an FP64
/// kernel of this size reaches only with tens of thousands of threads). A smaller group is
/// handed out where an excitation has fewer cases left in a hand-out window.
constexpr std::int64_t kGpuGroupCases = 65536;

/// Cases a master hands out in one window when the ranks are GPU ranks: a few groups.
constexpr std::int64_t kGpuWindowCases = 4 * kGpuGroupCases;

/// Where `[run] device` was given: the flag or keyword when the run's options override it,
/// else the study file's key (or the file alone).
Where device_where(const StudyRunOptions& options, const study::Study& study);

/// The GPU backend: gpu_group, or what a test gives (StudyRunOptions::gpu_backend).
using GpuBackend = std::function<std::unique_ptr<CaseGroupSolver>(std::string& why_not)>;

/// The group solver of the study's [run] device: the CPU engine's (make_group_solver,
/// Study::run.lanes wide), or the case kernel on a CUDA device (`gpu`, by default
/// gpu_group), the CPU engine solving the cases the kernel refuses (a scene, integrator or
/// output it does not cover). \throws UserError at `where` naming why no usable device is
/// there (a build without PCRF_CUDA, no device, a driver too old: gpu_group's reason).
std::shared_ptr<const CaseGroupSolver> device_group_solver(const study::Study& study, const Where& where,
                                                           const GpuBackend& gpu = {});

/// What the user should know of a GPU group (device_group_solver's) after a run: how many
/// cases its kernel refused and the CPU engine solved, with the first one's reason; empty
/// when none (or for the CPU engine's group).
std::string gpu_refusal_note(const CaseGroupSolver& group);

/// True when the study's cases are solved on a GPU.
inline bool on_gpu(const study::Study& study) { return study.run.device == study::Device::kGpu; }

}  // namespace pcrf::run
