// What `pcrf run|frame` and pcrf.run / pcrf.Frame both do with a scene request (see frame_input.hpp).
#include "pcrf/api/frame_input.hpp"

#include <cctype>
#include <stdexcept>

#include "pcrf/api/input_error.hpp"
#include "pcrf/setting.hpp"

namespace pcrf::api {
namespace {

/// `text` with each whole-word `word` (letters, digits and '_' around it end a word) replaced.
std::string replace_word(std::string text, const std::string& word, const std::string& by) {
  auto part_of_word = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
  for (std::size_t at = text.find(word); at != std::string::npos; at = text.find(word, at)) {
    const std::size_t end = at + word.size();
    if ((at > 0 && part_of_word(text[at - 1])) || (end < text.size() && part_of_word(text[end]))) {
      at = end;
      continue;
    }
    text.replace(at, word.size(), by);
    at += by.size();
  }
  return text;
}

}  // namespace

std::string scene_flag(std::string_view key) { return key == "given_restitution" ? "--restitution" : flag_name(key); }

std::unique_ptr<Scene> scene_of(const std::string& model_name, const std::map<std::string, double, std::less<>>& values,
                                ScenePoint* point) {
  const SceneModel* model = nullptr;
  try {
    model = &scene_model(model_name);
  } catch (const std::invalid_argument& e) {
    throw InputError(std::string("--model: ") + e.what());
  }
  try {
    ScenePoint made = scene_point(*model, values);
    auto scene = model->make(made);
    if (point != nullptr) *point = std::move(made);
    return scene;
  } catch (const std::invalid_argument& e) {
    // The catalogue names keys (given_restitution: …); both front ends name flags.
    std::string text = e.what();
    for (const auto& entry : values) text = replace_word(text, entry.first, scene_flag(entry.first));
    throw InputError(text);
  }
}

void check_pushover_points(int points) {
  if (points < 2) throw InputError("--points must be at least 2");
}

}  // namespace pcrf::api
