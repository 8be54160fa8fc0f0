"""The one failure a figure command reports: a line on stderr and exit code 2."""

import json


class PlotError(Exception):
    """Bad input, a missing piece, or a cube that lacks what the kind needs."""


def read_command_json(path, command, needed):
    """The JSON object that `command` printed into `path`, with every key of `needed`; else a
    PlotError naming the file and what it lacks."""
    try:
        with open(path, encoding="utf-8") as f:
            data = json.load(f)
    except (OSError, ValueError) as e:
        raise PlotError(f"{path}: cannot read the JSON of {command} ({e})") from None
    missing = [k for k in needed if not isinstance(data, dict) or k not in data]
    if missing:
        raise PlotError(f"{path}: not the JSON of {command} (no {', '.join(missing)})")
    return data
