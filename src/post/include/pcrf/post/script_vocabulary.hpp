/// \file script_vocabulary.hpp
/// \brief The names every script and figure needs besides a cube's own, as one JSON object
/// (`pcrf settings --json`, `pcrf.vocabulary()`): the statuses with what they say about the
/// frame, the history event flags, the frame parameters in axis order, an IDA's curve states,
/// and the cube's own names from its schema (its coordinates, variables and attributes by
/// role; the metrics, and those other layers act on by meaning).
#pragma once

#include <string>

namespace pcrf::post {

/// {"curve_states": [{name, value}], "statuses": [{name, value, kind: survived | collapse |
/// no_verdict}], "history_events": [{name, flag, meaning}], "parameters": [{name, long_name,
/// units}], "cube_names": {ROLE: name} (cube_vocabulary's cube_names), "metrics": [{name, units}],
/// "metric_roles": {"THETA_MAX": name, …}}, the not-run status included, on one line.
std::string script_vocabulary_json();

}  // namespace pcrf::post
