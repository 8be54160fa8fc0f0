"""The one failure a figure command reports: a line on stderr and exit code 2."""


class PlotError(Exception):
    """Bad input, a missing piece, or a cube that lacks what the kind needs."""
