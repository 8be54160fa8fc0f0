"""pcrf.open_cube: a result cube as an xarray.Dataset, status as integer flags."""


def _meant(value):
    """A coordinate value as the study wrote it: range-generated values in older cubes are
    start + i * step (1.7999999999999998 for 1.8); 15 significant digits recover the decimal."""
    return float(f"{value:.15g}")


def open_cube(path, **open_dataset_keywords):
    """The cube at ``path`` as an xarray.Dataset (opened lazily, as ``xarray.open_dataset``):

    - ``status`` is the integer the engine stores (int8), with ``flag_values`` and
      ``flag_meanings`` (CF) in its attributes, -1 for a case not computed; not the float32 with
      NaN that plain xarray makes of it. ``ds.status.attrs["flag_meanings"].split()`` names them.
    - float coordinates are the values the study meant, so ``ds.sel(kappa=1.8)`` works.
    """
    import numpy as np
    import xarray as xr

    ds = xr.open_dataset(path, **open_dataset_keywords)
    if "status" in ds.variables and ds["status"].dtype.kind == "f":  # a cube written with a _FillValue
        with xr.open_dataset(path, mask_and_scale=False) as raw:
            status = raw["status"].load()
        fill = status.attrs.pop("_FillValue", None)
        if fill is not None:
            status.encoding["_FillValue"] = fill
        ds["status"] = status
    for name, coordinate in ds.coords.items():
        if coordinate.ndim == 1 and np.issubdtype(coordinate.dtype, np.floating):
            ds = ds.assign_coords({name: (coordinate.dims, np.array([_meant(v) for v in coordinate.values]),
                                          coordinate.attrs)})
    return ds
