/// \file input_error.hpp
/// \brief The error every check of a user's input throws in the layer that both front ends
/// call (the `pcrf` command line and the Python module): one line naming the input and the
/// problem. The command line prints it and exits with code 2; the module raises ValueError
/// with the same text.
#pragma once

#include <stdexcept>

namespace pcrf::api {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace pcrf::api
