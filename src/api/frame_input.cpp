// What `pcrf run|frame` and pcrf.run / pcrf.Frame both do with a scene request (see frame_input.hpp).
#include "pcrf/api/frame_input.hpp"

#include "pcrf/user_error.hpp"

namespace pcrf::api {

std::unique_ptr<Scene> scene_of(const std::string& model_name, const std::map<std::string, double, std::less<>>& values,
                                ScenePoint* point) {
  const SceneModel& model = scene_model(model_name);
  ScenePoint made = scene_point(model, values);
  auto scene = model.make(made);
  if (point != nullptr) *point = std::move(made);
  return scene;
}

void check_pushover_points(int points) {
  if (points < 2) throw UserError("points", "must be at least 2");
}

}  // namespace pcrf::api
