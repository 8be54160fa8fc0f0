/// \file fingerprint.hpp
/// \brief A short hash of everything that determines a study's results, so that --resume
/// can tell "the same study" from "another study" whatever the file's comments or layout.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "pcrf/study/case_space.hpp"
#include "pcrf/study/record_source.hpp"
#include "pcrf/study/study.hpp"

namespace pcrf::study {

/// 64-bit FNV-1a of `bytes`, continuing from `hash`.
std::uint64_t fnv1a(std::string_view bytes, std::uint64_t hash = 14695981039346656037ull);

/// Canonical description of what the study computes: plan, records (name, sampling and a
/// hash of their samples), axes, base point, cases, physics, solver, metrics, histories.
/// Run options (flush, progress, batch size) and the study's name are not part of it.
std::string canonical_description(const Study& study, const CaseSpace& space, RecordCache& records);

/// 16 hex digits: fnv1a of canonical_description().
std::string study_fingerprint(const Study& study, const CaseSpace& space, RecordCache& records);

}  // namespace pcrf::study
