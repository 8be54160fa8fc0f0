// What `pcrf frame` and pcrf.Frame both check (see frame_input.hpp).
#include "pcrf/api/frame_input.hpp"

#include "pcrf/api/input_error.hpp"

namespace pcrf::api {

void check_pushover_points(int points) {
  if (points < 2) throw InputError("--points must be at least 2");
}

}  // namespace pcrf::api
