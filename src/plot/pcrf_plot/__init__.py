"""Figures of pcrf results, drawn with matplotlib; run as ``pcrf plot KIND INPUT -o FILE``.

The numbers come from the ``pcrf`` executable itself (``cube info --json``, ``cube export``,
``cube stats``, ``cube fragility``, ``cube sensitivity``), so every estimator and every
selection (``-w NAME=VALUE``) is the engine's; this package only draws.
"""
