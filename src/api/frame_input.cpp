// What `pcrf run|frame` and pcrf.run / pcrf.Frame both do with a scene request (see frame_input.hpp).
#include "pcrf/api/frame_input.hpp"

#include "pcrf/user_error.hpp"

#include <cmath>
#include <string>

#include "pcrf/number_text.hpp"

namespace pcrf::api {

std::unique_ptr<Scene> scene_of(const std::string& model_name, const std::map<std::string, double, std::less<>>& values,
                                ScenePoint* point) {
  const SceneModel& model = scene_model(model_name);
  ScenePoint made = scene_point(model, values);
  auto scene = model.make(made);
  if (point != nullptr) *point = std::move(made);
  return scene;
}

int pushover_points(double points) {
  const std::string most = std::to_string(kMaxPushoverPoints);
  if (!(points >= 2.0)) throw UserError("points", "must be at least 2 (and at most " + most + "), not " + number_text(points));
  if (!(points <= kMaxPushoverPoints)) throw UserError("points", "must be at most " + most + ", not " + number_text(points));
  if (points != std::floor(points)) throw UserError("points", "must be a whole number, not " + number_text(points));
  return static_cast<int>(points);
}

}  // namespace pcrf::api
