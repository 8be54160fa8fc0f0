// Helpers of CubeLayout (see cube_layout.hpp).
#include "pcrf/cube/cube_layout.hpp"

#include "pcrf/number_text.hpp"

#include <cerrno>
#include <charconv>

namespace pcrf::cube {

CubeError::Cause CubeError::cause_of(int os_error) {
  if (os_error == ENOSPC || os_error == EDQUOT) return Cause::kNoSpace;
  if (os_error == ENOENT) return Cause::kGone;
  return Cause::kOther;
}


std::string Coordinate::label(std::size_t i) const {
  if (is_text) return text(i);
  return number_text(number(i));
}

void Coordinate::numbers_into(std::size_t first, std::span<double> out) const {
  if (first > size() || out.size() > size() - first)
    throw std::out_of_range("coordinate '" + name + "' has no values " + std::to_string(first) + " … " +
                            std::to_string(first + out.size() - 1));
  if (numbers_from) return numbers_from(first, out);
  for (std::size_t k = 0; k < out.size(); ++k) out[k] = number(first + k);
}

void Coordinate::release_values() {
  std::vector<double>().swap(numbers);
  std::vector<std::string>().swap(strings);
  number_at = nullptr;
  numbers_from = nullptr;
  text_at = nullptr;
}

std::int64_t CubeLayout::case_count() const {
  std::int64_t count = 1;
  for (const auto& d : dimensions) count *= static_cast<std::int64_t>(d.size);
  return count;
}

std::vector<std::size_t> CubeLayout::shape() const {
  std::vector<std::size_t> result;
  for (const auto& d : dimensions) result.push_back(d.size);
  return result;
}

std::vector<std::string> CubeLayout::auxiliary_names() const {
  std::vector<std::string> names;
  for (const auto& c : coordinates)
    if (c.name != c.dimension) names.push_back(c.name);
  return names;
}

const Coordinate* CubeLayout::find_coordinate(const std::string& name) const {
  for (const auto& c : coordinates)
    if (c.name == name) return &c;
  return nullptr;
}

std::optional<std::size_t> CubeLayout::find_dimension(const std::string& name) const {
  for (std::size_t d = 0; d < dimensions.size(); ++d)
    if (dimensions[d].name == name) return d;
  return std::nullopt;
}

const SideVariable* CubeLayout::find_side_variable(const std::string& name) const {
  for (const auto& v : side_variables)
    if (v.name == name) return &v;
  return nullptr;
}

std::size_t CubeLayout::side_size(const SideVariable& variable) const {
  std::size_t n = 1;
  for (const auto& name : variable.dimensions)
    if (const auto d = find_dimension(name)) n *= dimensions[*d].size;
  return n;
}

std::string CubeLayout::text_attribute(const std::string& name) const {
  for (const auto& a : attributes)
    if (a.name == name)
      if (const auto* text = std::get_if<std::string>(&a.value)) return *text;
  return {};
}

}  // namespace pcrf::cube
