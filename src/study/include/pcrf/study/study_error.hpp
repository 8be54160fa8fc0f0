/// \file study_error.hpp
/// \brief The error every study-layer check throws.
#pragma once

#include <stdexcept>

namespace pcrf::study {

/// A study cannot run as written. what() reads "FILE:LINE: KEY: problem" (LINE where known).
class StudyError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace pcrf::study
