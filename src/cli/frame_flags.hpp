/// \file frame_flags.hpp
/// \brief The flags that describe a frame (--kappa … --pi-e-c, --h-m, --m-c-kg), from the
/// parameter tables, for every command that takes a frame.
#pragma once

#include <CLI/CLI.hpp>

#include "pcrf/model/frame.hpp"

namespace pcrf::cli {

/// Adds the frame's flags to `cmd`; their values land in `frame` (default: the basic model).
void add_frame_flags(CLI::App* cmd, FrameParameters& frame);

/// The frame the flags describe. \throws UsageError naming the impossible parameter.
Frame frame_from_flags(const FrameParameters& frame);

}  // namespace pcrf::cli
