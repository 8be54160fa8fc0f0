# %% [markdown]
# # pcrf in Python: a session
# The cells of a Jupyter notebook (`# %%` marks a cell; VS Code and Jupytext open it as one).
# Run it as a script from the checkout's folder after building:
#     PYTHONPATH=build/python python3 examples/notebook.py
# ctest runs it end to end (tests/python/test_notebook.py). It writes `notebook_demo.h5` in
# the working directory.

# %%
import concurrent.futures
import time

import numpy as np

import pcrf

print("pcrf", pcrf.__version__)

# %% [markdown]
# ## A frame before any ground motion (`pcrf frame`)

# %%
basic = pcrf.Frame()
stocky = pcrf.Frame(kappa=2.5, tan_alpha=0.25)
for frame in (basic, stocky):
    print(f"{frame!r}: uplift at {frame.threshold:.3f} g, r = {frame.restitution:.3f}, "
          f"p = {frame.frequency_parameter_rad_s:.2f} rad/s, capacity {frame.capacity_g:.2f} g")
print("pushover of the basic frame [g]:", np.round(basic.pushover_accel_g[:5], 3), "...")

# %% [markdown]
# ## One case from a generated motion, with its history as a DataFrame (`pcrf run`)

# %%
dt_s = 0.005
t = np.arange(0.0, 3.0, dt_s)
pulse_g = np.where(t < 1.0, 1.6 * np.sin(2 * np.pi * t / 0.5), 0.0)  # two cycles of a 0.5 s sine
result, history = pcrf.run(pulse_g, dt_s, frame=basic, preset="reference", tail_s=2.0, history="pandas")
print({key: result[key] for key in ("status", "theta_max_rad", "t_uplift_s", "impacts", "cpu_time_s")})
events = history[history["event"] > 0]
print(f"{len(history)} rows, {len(events)} with events; the peak row:")
print(history.loc[history["theta1_rad"].abs().idxmax(), ["t_s", "theta1_rad", "omega1_rad_s"]])

# %% [markdown]
# ## Many cases on every core: a thread pool (the engine releases the GIL)

# %%
amplitudes_g = np.linspace(1.1, 2.6, 16)


def peak(amplitude_g):
    return pcrf.run(amplitude_g / 1.6 * pulse_g, dt_s, preset="balanced")["theta_max_rad"]


start = time.perf_counter()
with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
    peaks = list(pool.map(peak, amplitudes_g))
print(f"{len(peaks)} cases in {time.perf_counter() - start:.2f} s on 2 threads")
for a, theta in zip(amplitudes_g[::5], peaks[::5]):
    print(f"  {a:.2f} g -> theta_max {theta:.4g} rad")

# %% [markdown]
# ## A bad keyword or value: pcrf.InputError (a ValueError) naming the keyword

# %%
for bad in ({"tail_s": -1}, {"preset": "fastest"}, {"rtoll": 1e-6}):
    try:
        pcrf.run(pulse_g, dt_s, **bad)
    except ValueError as error:
        print(f"{bad}: {error}")

# %% [markdown]
# ## A study from a dict, in process, as an xarray.Dataset (`pcrf study`)

# %%
cube = pcrf.study(
    {
        "study": {"name": "notebook"},
        "plan": {"kind": "grid"},
        "records": [{"synthetic": ["sine:amplitude_g=1.5,period_s=0.5,cycles=2,duration_s=4"]}],
        "axes": {"scale": [0.8, 1.0, 1.25], "kappa": {"from": 1.2, "to": 2.4, "count": 3}},
        "physics": {"tail_s": 1.0},
    },
    output="notebook_demo.h5",
    overwrite=True,
)
print(cube["theta_max_rad"].sel(kappa=1.8).squeeze().to_pandas())
meanings = cube["status"].attrs["flag_meanings"].split()
print("statuses:", {meanings[list(cube["status"].attrs["flag_values"]).index(v)]: int((cube["status"] == v).sum())
                    for v in np.unique(cube["status"].values)})
