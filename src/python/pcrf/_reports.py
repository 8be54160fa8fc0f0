"""pcrf.stats, fragility, sensitivity, p695, risk: the command line's cube reports as pandas
DataFrames, from the JSON that `pcrf cube KIND --json` writes (the same C++, full precision)."""

import json
import os

from . import _pcrf
from ._notices import warn


def report(kind, cube, **keywords):
    """The object ``pcrf cube KIND CUBE --json`` writes (the same C++), as dicts and lists; what
    ``pcrf cube KIND`` prints on stderr beside it (the cube's notes, then the report's warnings)
    is warned, each a ``pcrf.PcrfWarning``."""
    answer, notes = said(kind, cube, **keywords)
    warn(notes + answer.get("warnings", []))
    return answer


def said(kind, cube, **keywords):
    """(the report's object, the notes ``pcrf cube KIND`` prints before it), nothing warned: the
    figures, which say their cube's notes themselves, draw from it."""
    text, notes = _pcrf.cube_report(kind, os.fspath(cube), **keywords)
    return json.loads(text), notes


def _frame(kind, cube, table, **keywords):
    """The report's table `table` as a DataFrame; ``attrs`` holds the report's fields, its
    warnings (also warned: ``pcrf.PcrfWarning``), the columns' units and descriptions, and its
    other tables (as DataFrames)."""
    import pandas

    answer = report(kind, cube, **keywords)
    columns = answer.pop("columns")
    tables = {name: pandas.DataFrame(answer.pop(name), columns=[c["name"] for c in spec])
              for name, spec in columns.items()}
    result = tables.pop(table)
    result.attrs.update(
        command=answer.pop("command"), warnings=answer.pop("warnings", []), fields=answer,
        units={c["name"]: c["units"] for c in columns[table]},
        descriptions={c["name"]: c["description"] for c in columns[table]}, tables=tables)
    return result


def stats(cube, by, metric, where=None, reduce_over=None, reduce=None):
    """``pcrf cube stats``: median and 16th/84th percentiles of ``metric`` across records per
    value of ``by`` (a coordinate or a list); ``where`` a dict or "name=value" texts.
    ``reduce_over`` (``--reduce-over``, e.g. "incidence_deg") first reduces the metric over that
    dimension, by ``reduce`` (``--reduce``): "max" (the default: each record and frame's worst
    orientation, RotD100), "median" (RotD50) or "min" (an IDA's ``collapse_intensity`` at its worst)."""
    return _frame("stats", cube, "groups", by=by, metric=metric, where=where, reduce_over=reduce_over,
                  reduce=reduce)


def fragility(cube, where=None, mce=None, table="frames", reduce_over=None, reduce=None):
    """``pcrf cube fragility``: the lognormal collapse fragility of each frame (median, beta and
    their 90 % intervals; ``cmr`` with ``mce``); ``table="points"`` for the data fitted.
    ``reduce_over`` (an IDA cube, e.g. "incidence_deg") first reduces each record's collapse
    intensities over that dimension, by ``reduce``: "min" (the default: its worst orientation),
    "median" or "max", as ``--reduce-over`` and ``--reduce`` do."""
    return _frame("fragility", cube, table, where=where, mce=mce, reduce_over=reduce_over, reduce=reduce)


def sensitivity(cube, metric, where=None, by_record=False):
    """``pcrf cube sensitivity``: Sobol' indices of each parameter of a saltelli cube."""
    return _frame("sensitivity", cube, "indices", metric=metric, where=where, by_record=by_record)


def p695(cube, period_s, sdc="Dmax", mu_t=0.0, ratings=None, where=None, s_ct="counted"):
    """``pcrf cube p695``: FEMA P-695 per frame; the group's verdict in ``attrs["fields"]``. ``mu_t=0``: each
    frame's own period-based ductility (docs/p695_rocking_frame.md), as the command line's default.
    ``ratings=None``: B,B,B, noted in the warnings as the default. ``s_ct``: "counted" (P-695's own,
    Sections 6.3-6.4) or "lognormal" (the fitted fragility's median) feeds CMR and ACMR."""
    return _frame("p695", cube, "frames", period_s=period_s, sdc=sdc, mu_t=mu_t, ratings=ratings or "", where=where,
                  s_ct=s_ct)


def risk(cube, hazard, years=50.0, tail="power-law", target_probability=0.01, target_years=50.0, generic_beta=0.6,
         generic_probability=0.1, ratings="B,B,B", where=None, table="frames"):
    """``pcrf cube risk``: each frame's annual collapse rate at the site of the hazard curve CSV ``hazard``
    (lognormal and empirical side by side), its probability in ``years``, the factor on the hazard at the
    risk target; ``attrs["fields"]`` holds the risk-targeted intensity and the group; ``table=
    "deaggregation"`` for λ_c over intensity bins (also "hazard", "empirical"). See docs/risk.md."""
    return _frame("risk", cube, table, hazard=os.fspath(hazard), years=years, tail=tail,
                  target_probability=target_probability, target_years=target_years, generic_beta=generic_beta,
                  generic_probability=generic_probability, ratings=ratings, where=where)
