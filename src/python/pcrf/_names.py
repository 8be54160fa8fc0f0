"""The names of a result cube, read once from the engine's schema (``pcrf.vocabulary()``, the
C++ ``cube_vocabulary``): the package spells none of them.

- coordinates, variables and attributes by role: ``RECORD``, ``INTENSITY``, ``IDA_INTENSITY``,
  ``COLLAPSE_INTENSITY``, ``CURVE_STATE``, ``STATUS``, ``CASE``, ``CASE_LABEL``, … (the
  schema's ``cube_names()``: ``IDA_INTENSITY`` is ``kIdaIntensity``);
- metrics by the role the engine knows them by: ``THETA_MAX``, ``OMEGA_MAX``, ``IMPACTS``, …
  (``metric::theta_max()``, …); ``METRICS``, every metric's name in the engine's order.

An unknown role is an AttributeError when the module reads it: a name the schema dropped fails
at once, never as a column quietly missing.
"""

import json as _json

from . import _pcrf

_VOCABULARY = _json.loads(_pcrf.vocabulary())
_ROLES = {**_VOCABULARY["cube_names"], **_VOCABULARY["metric_roles"]}

METRICS = tuple(m["name"] for m in _VOCABULARY["metrics"])


def __getattr__(role):
    try:
        return _ROLES[role]
    except KeyError:
        raise AttributeError(f"the cube's schema has no name {role!r} (roles: {', '.join(sorted(_ROLES))})") from None


def __dir__():
    return sorted(set(globals()) | set(_ROLES))
