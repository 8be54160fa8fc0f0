"""Figures of pcrf results, drawn with matplotlib; run as ``pcrf plot KIND INPUT -o FILE``.

The numbers come from the ``pcrf`` executable itself as JSON (``cube info --json``, ``cube
stats --json``, ``cube fragility --json``, ``cube sensitivity --json``) and ``cube export``, and
so do the names (``pcrf settings --json``: statuses, history event flags, parameters), so
every estimator, selection (``-w NAME=VALUE``) and label is the engine's; this package only draws.
"""
