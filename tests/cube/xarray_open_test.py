"""A cube opened by plain xarray (no pcrf code): `status` is an integer with CF flags that
name every status, and range-generated coordinates select by the decimals a reader types. An
LHS of more than 4096 frames (its coordinates chunked, shuffled and deflated, no per-case label
stored) opens with every coordinate, equal to what `pcrf cube export` prints.

Run by ctest: python3 xarray_open_test.py PCRF SCRATCH_DIR. Exit code 77 (skipped) when
xarray or netCDF4 is missing.
"""
import os
import subprocess
import sys

try:
    import numpy as np
    import xarray as xr
    import netCDF4  # noqa: F401 (the engine xarray uses for netCDF-4 files)
except ImportError as e:
    print(f"skipped: {e}")
    sys.exit(77)

STUDY = """[[records]]
synthetic = ["sine:amplitude_g=1.5,period_s=0.5,cycles=2,duration_s=3", "sine:amplitude_g=3,period_s=0.7,cycles=2,duration_s=3"]
[axes]
scale = [1.0, 2.5]
kappa = {from = 1.2, to = 2.4, count = 7}
lambda_h = {from = 0.1, to = 0.3, count = 3}
"""


def run_study(pcrf, folder, name, text, *options):
    """The cube of study `text`, run as <folder>/<name>.toml into <folder>/<name>.h5 (`options`:
    more of `pcrf study`'s)."""
    study = os.path.join(folder, name + ".toml")
    cube = os.path.join(folder, name + ".h5")
    with open(study, "w", encoding="utf-8") as f:
        f.write(text)
    subprocess.run([pcrf, "study", study, "-o", cube, "--overwrite", "--progress-interval", "0", *options],
                   check=True, capture_output=True)
    return cube


def exported_rows(pcrf, cube):
    """`pcrf cube export` of `cube`, a dict a case."""
    import csv
    import io
    return list(csv.DictReader(io.StringIO(subprocess.run(
        [pcrf, "cube", "export", cube, "--no-record-text"], check=True, capture_output=True, text=True).stdout)))


def main(pcrf, folder):
    os.makedirs(folder, exist_ok=True)
    # --shard 1/2 leaves half of the cases not run: their status is the not_run flag, not NaN.
    cube = run_study(pcrf, folder, "ranges", STUDY, "--shard", "1/2")
    settings = subprocess.run([pcrf, "settings", "--json"], check=True, capture_output=True, text=True).stdout
    import json
    names = {s["name"]: s["value"] for s in json.loads(settings)["statuses"]}

    for engine in ("netcdf4", "h5netcdf"):
        try:
            ds = xr.open_dataset(cube, engine=engine)
        except (ValueError, ImportError) as e:  # h5netcdf not installed
            print(f"{engine}: skipped ({e})")
            continue
        status = ds["status"]
        assert np.issubdtype(status.dtype, np.integer), f"{engine}: status is {status.dtype}"
        flags = dict(zip(status.attrs["flag_meanings"].split(), np.asarray(status.attrs["flag_values"]).tolist()))
        assert flags == names, f"{engine}: flags {flags} against the engine's {names}"
        present = set(np.unique(status.values).tolist())
        assert names["not_run"] in present and present <= set(names.values()), present
        assert "_FillValue" not in status.encoding or status.encoding["_FillValue"] is None, status.encoding
        # Range values are the decimals the study meant: .sel with the typed number works.
        assert ds.kappa.values.tolist() == [1.2, 1.4, 1.6, 1.8, 2.0, 2.2, 2.4], ds.kappa.values.tolist()
        assert ds.lambda_h.values.tolist() == [0.1, 0.2, 0.3], ds.lambda_h.values.tolist()
        one = ds.theta_max_rad.sel(kappa=1.8, lambda_h=0.3, scale=2.5)
        assert one.sizes["record"] == 2
        assert int(ds.status.sel(kappa=1.8, lambda_h=0.2, scale=1.0).isel(record=0)) in names.values()
        ds.close()
        print(f"{engine}: status {status.dtype}, kappa {ds.kappa.values.tolist()}")


LHS = """[[records]]
synthetic = "sine:amplitude_g=0.05,period_s=0.5,cycles=1,duration_s=0.5"
[plan]
kind = "lhs"
samples = 5000
seed = 7
[axes]
kappa = {from = 1.2, to = 2.4}
tan_alpha = {from = 0.15, to = 0.25}
[outputs]
metrics = ["theta_max_rad"]
"""


def lhs_coordinates(pcrf, folder):
    """A long LHS: xarray reads its compressed coordinates as the engine wrote them."""
    cube = run_study(pcrf, folder, "lhs", LHS)
    rows = exported_rows(pcrf, cube)
    for engine in ("netcdf4", "h5netcdf"):
        try:
            ds = xr.open_dataset(cube, engine=engine)
        except (ValueError, ImportError) as e:
            print(f"{engine}: skipped ({e})")
            continue
        assert "case_label" not in ds.variables, list(ds.variables)
        assert ds.sizes["case"] == 5000, ds.sizes
        for name in ("case", "kappa", "tan_alpha", "lambda", "lambda_h", "pi_e_c"):
            assert name in ds.coords, f"{engine}: no coordinate {name} in {list(ds.coords)}"
        kappa = ds.kappa.values.tolist()
        assert [float(r["kappa"]) for r in rows] == kappa, f"{engine}: kappa differs from the export"
        assert ds.case.values.tolist() == list(range(5000))
        ds.close()
        print(f"{engine}: lhs of 5000 frames, coordinates {sorted(ds.coords)}")


CHECKPOINT = LHS.replace("samples = 5000", "samples = 20000")


def checkpoint_coordinates(pcrf, folder):
    """A cube as a checkpoint's fold leaves it mid-run (issue 38): a sampled plan's parameters
    are written with their units, so the cases of a unit not in the cube yet have NaN there
    (the variable's _FillValue), their status not run. xarray masks them (NaN, never a value),
    `pcrf cube export` writes no value for them, and `pcrf cube info` reads the cube. Made from
    a closed cube whose second unit (cases 16 384 on) is taken out again, as the writer lays a
    live coordinate out: chunks of the metrics' 16 384 cases, fill NaN, the later chunk not
    written. Needs h5py (skipped without)."""
    try:
        import h5py
    except ImportError as e:
        print(f"checkpoint: skipped ({e})")
        return
    cube = run_study(pcrf, folder, "checkpoint", CHECKPOINT)
    unit = 16384
    with h5py.File(cube, "r+") as f:
        kappa = f["kappa"]
        assert kappa.chunks == (unit,), f"kappa is chunked {kappa.chunks}, not as the metrics along case"
        assert np.isnan(kappa.fillvalue), kappa.fillvalue
        values, attrs = kappa[...], dict(kappa.attrs)
        del f["kappa"]
        again = f.create_dataset("kappa", shape=values.shape, dtype="<f8", chunks=(unit,), shuffle=True,
                                 compression="gzip", compression_opts=1, fillvalue=np.nan)
        again[:unit] = values[:unit]  # the first unit's chunk only
        for name, value in attrs.items():
            if name not in ("DIMENSION_LIST", "REFERENCE_LIST"):
                again.attrs[name] = value
        again.dims[0].attach_scale(f["case"])
        f["status"][..., unit:] = -1
        f["theta_max_rad"][..., unit:] = np.nan
    ds = xr.open_dataset(cube)
    kappa = ds.kappa.values
    assert not np.isnan(kappa[:unit]).any(), "the first unit's kappa"
    assert np.isnan(kappa[unit:]).all(), "a unit not written yet reads as no value"
    assert (ds.status.values[..., unit:] == -1).all()
    ds.close()
    rows = exported_rows(pcrf, cube)
    assert [float(r["kappa"]) for r in rows[:unit]] == kappa[:unit].tolist()
    assert all(r["kappa"] == "" and r["status"] == "not_run" for r in rows[unit:]), rows[unit]
    info = subprocess.run([pcrf, "cube", "info", cube], check=True, capture_output=True, text=True).stdout
    assert f"completion: {unit}/20000" in info, info
    print(f"checkpoint: kappa of {unit} cases written, {20000 - unit} not yet (NaN)")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
    lhs_coordinates(sys.argv[1], sys.argv[2])
    checkpoint_coordinates(sys.argv[1], sys.argv[2])
