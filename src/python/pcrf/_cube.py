"""pcrf.open_cube: a result cube as an xarray.Dataset, status as integer flags."""

import os

from . import _names as schema
from . import _pcrf
from ._notices import warn


def _meant(value):
    """A coordinate value as the study wrote it: range-generated values in older cubes are
    start + i * step (1.7999999999999998 for 1.8); 15 significant digits recover the decimal."""
    return float(f"{value:.15g}")


def open_cube(path, pulse_dimensions=False, **open_dataset_keywords):
    """The cube at ``path`` as an xarray.Dataset (opened lazily, as ``xarray.open_dataset``):

    - ``status`` is the integer the engine stores (int8), with ``flag_values`` and
      ``flag_meanings`` (CF) in its attributes, -1 for a case not computed; not the float32 with
      NaN that plain xarray makes of it. ``ds.status.attrs["flag_meanings"].split()`` names them.
    - float coordinates are the values the study meant, so ``ds.sel(kappa=1.8)`` works.
    - ``pulse_dimensions=True``, for a study of pulses (``[[records]] pulse`` with pulse axes):
      the ``record`` dimension is unstacked into one dimension per pulse coordinate
      (``pulse_shape``, ``pulse_period_s``, …), so that ``ds.sel(pulse_shape="ricker")`` and
      ``ds.collapse_intensity.plot(x="pulse_period_s")`` work; the engine keeps pulses along
      ``record``, as motions, since a study may mix pulses and records. Combinations the study
      did not run are NaN (status -1). ValueError for a cube whose records are not all pulses.

    What ``pcrf cube info`` says of the cube on stderr (a run is writing it, results wait in its
    journal, cases were not run) is warned, each a ``pcrf.PcrfWarning``.
    """
    try:
        warn(_pcrf.cube_notes(str(path)))
    except _pcrf.InputError:
        pass  # not a cube the engine reads: xarray says what it makes of the file
    return opened(path, pulse_dimensions, **open_dataset_keywords)


def opened(path, pulse_dimensions=False, **open_dataset_keywords):
    """open_cube without its notes: pcrf.study's cube, whose run said what it had to."""
    import numpy as np
    import xarray as xr

    if isinstance(path, (str, bytes)) or hasattr(path, "__fspath__"):
        _pcrf.check_cube_file(os.fsdecode(path))  # a FIFO would make netCDF wait for ever: refused at once
    ds = xr.open_dataset(path, **open_dataset_keywords)
    if schema.STATUS in ds.variables and ds[schema.STATUS].dtype.kind == "f":  # a cube written with a _FillValue
        with xr.open_dataset(path, mask_and_scale=False) as raw:
            status = raw[schema.STATUS].load()
        fill = status.attrs.pop("_FillValue", None)
        if fill is not None:
            status.encoding["_FillValue"] = fill
        ds[schema.STATUS] = status
    for name, coordinate in ds.coords.items():
        if coordinate.ndim == 1 and np.issubdtype(coordinate.dtype, np.floating):
            ds = ds.assign_coords({name: (coordinate.dims, np.array([_meant(v) for v in coordinate.values]),
                                          coordinate.attrs)})
    return _pulses_unstacked(ds) if pulse_dimensions else ds


def _pulses_unstacked(ds):
    """``record`` unstacked into the pulse coordinates along it (the engine names them)."""
    levels = [name for name in _pcrf.pulse_coordinates() if name in ds.coords and ds.coords[name].dims == (schema.RECORD,)]
    if schema.PULSE_SHAPE not in levels or any(shape == "" for shape in ds[schema.PULSE_SHAPE].values):
        raise ValueError(f"pulse_dimensions=True: the cube's records are not all pulses (its {schema.PULSE_SHAPE} is "
                         + ("missing" if schema.PULSE_SHAPE not in levels else "empty for some") + ")")
    import numpy as np

    stacked = ds.set_index({schema.RECORD: levels})
    # Every variable needs its own filler (older xarray takes none by default from a dict).
    fill = {name: -1 if v.dtype.kind == "i" else np.nan if v.dtype.kind == "f" else ""
            for name, v in stacked.variables.items() if schema.RECORD in v.dims}
    return stacked.unstack(schema.RECORD, fill_value=fill)
