/// \file group_answers.hpp
/// \brief What every backend of a group of cases (case_group.hpp) answers alike: a refused
/// case, and the one-case rule of a history. Private to the solver.
#pragma once

#include <cstddef>
#include <string>

#include "pcrf/solver/case_group.hpp"

namespace pcrf::detail {

/// The answer of a refused case: why, and nothing else set.
GroupCase refused_case(std::string why);

/// \throws std::invalid_argument where a history is asked of a group of more than one case.
void check_group_history(std::size_t cases, const HistorySink& history);

}  // namespace pcrf::detail
