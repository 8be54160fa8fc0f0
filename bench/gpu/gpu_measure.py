#!/usr/bin/env python3
"""GPU measurement (issue 40, item 5; docs/gpu.md): one prepared run on a machine with one
NVIDIA H100/H200 and 16 cores, within 6 minutes. Not a test.

    python3 bench/gpu/gpu_measure.py --pkg .gpu-pkg [--out DIR]          # there
    python3 bench/gpu/gpu_measure.py --smoke                             # here: tiny, host path

What it runs, each step under a time limit so that the whole fits (a step cut short reports
what it did):
1. Per scene (the block: an LHS of alpha in [0.15, 0.25] rad, p in [1.5, 3] rad/s; the
   prestressed frame: tan alpha in [0.15, 0.25], Pi_sigma_c in [2, 10], kappa in [1, 2.5],
   docs/batches.md's designs), under ER1 and ER7 (the paper's far-field records), each
   scaled to twice the design's median uplift threshold (pcrf_gpu_bench --median-threshold-g):
   - the GPU: `pcrf_gpu_bench STUDY --backend gpu`, --cases (10^6) cases in groups of
     kGpuGroupCases (what a GPU rank is handed), cases per second of the backend's solve;
   - the same host's cores with the CPU engine: `mpirun -n 16 pcrf_gpu_bench STUDY --backend
     cpu`, the same study's cases shared out, each process's rate over its solve (at most
     --cpu-seconds each: the cases done are a random subset of the LHS), summed.
2. A whole `pcrf study --device gpu` of --study-cases (10^7) blocks under ER1 through the
   cube (--study-ranks ranks sharing the GPU), its wall time from start to closed cube; a
   run past its time is stopped by SIGTERM (the cube keeps what was done) and its rate is
   over the cases saved.
It prints a table (cases/s, the ratio to the cores, the device's name from nvidia-smi) and
writes it, with every raw JSON line, under --out ($OUT there).

--pkg: the folder bench/gpu/package.sh made (its env.sh is sourced: LD_LIBRARY_PATH, Open MPI's
OPAL_* folders, PATH). Where bench/gpu/build_cuda.sh exists (the case kernel's own build on
the device, if it needs one), it is run first with the package's environment; it may print
`PCRF_BIN_DIR=DIR` naming the folder of the pcrf and pcrf_gpu_bench to use.
--smoke: tiny sizes, 2 ranks, and where no GPU is usable the host build of the case kernel
stands in for the GPU (`--backend host-kernel`) and the study runs `--device cpu`; the table
says so in every such row.
"""
import argparse
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

RECORDS = {"ER1": "ER1_MUL279.AT2", "ER7": "ER7_CAP000.AT2"}
SCENES = {
    "block": ('[frame]\nmodel = "block"\ngiven_restitution = 0.9\n[axes]\n'
              "slenderness_rad = {{from = 0.15, to = 0.25}}\nfrequency_parameter_rad_s = {{from = 1.5, to = 3.0}}\n"
              "intensity = [{pga_g}]\n"),
    "frame": ("[axes]\ntan_alpha = {{from = 0.15, to = 0.25}}\npi_sigma_c = {{from = 2.0, to = 10.0}}\n"
              "kappa = {{from = 1.0, to = 2.5}}\nintensity = [{pga_g}]\n"),
}
STUDY = ('[study]\nname = "{name}"\n[plan]\nkind = "lhs"\nsamples = {samples}\nseed = 7\n'
         '[intensity]\nmeasure = "pga_g"\n[[records]]\nfile = "{record}"\n'
         '[outputs]\nmetrics = ["theta_max_rad", "impacts"]\n[solver]\npreset = "balanced"\nintegrator = "{integrator}"\n')


class Clock:
    """The run's deadline: each step gets at most what is left, less a reserve for the table."""

    def __init__(self, budget_s, reserve_s=15.0):
        self.end = time.monotonic() + budget_s - reserve_s

    def left(self):
        return max(self.end - time.monotonic(), 0.0)

    def limit(self, cap_s):
        return max(min(cap_s, self.left()), 1.0)


def log(text, out):
    print(text, flush=True)
    with open(out / "gpu_log.txt", "a") as f:
        f.write(text + "\n")


def environment(pkg):
    """The package's environment (env.sh sourced), or this one."""
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    if pkg is None:
        return env
    dump = subprocess.run(["bash", "-c", f'source "{pkg}/env.sh" >/dev/null && env -0'], capture_output=True,
                          env=env, check=True).stdout
    return dict(item.split("=", 1) for item in dump.decode().split("\0") if "=" in item)


def run(args, env, timeout_s, out, stop_signal=None):
    """(return code, stdout, stderr, wall seconds); a run past timeout_s gets stop_signal
    (SIGKILL by default) and return code None."""
    log("$ " + " ".join(str(a) for a in args) + f"   [limit {timeout_s:.0f} s]", out)
    start = time.monotonic()
    proc = subprocess.Popen([str(a) for a in args], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            env=env, start_new_session=True)
    try:
        stdout, stderr = proc.communicate(timeout=timeout_s)
        code = proc.returncode
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, stop_signal or signal.SIGKILL)
        try:
            stdout, stderr = proc.communicate(timeout=30)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            stdout, stderr = proc.communicate()
        code = None
    wall = time.monotonic() - start
    for line in (stderr or "").strip().splitlines()[-5:]:
        log("  stderr: " + line, out)
    return code, stdout or "", stderr or "", wall


def json_lines(text):
    rows = []
    for line in text.splitlines():
        line = line.strip()
        if line.startswith("{"):
            try:
                rows.append(json.loads(line))
            except json.JSONDecodeError:
                pass
    return rows


def device_name(env):
    if shutil.which("nvidia-smi", path=env.get("PATH")) is None:
        return "no NVIDIA device (nvidia-smi not found)"
    q = subprocess.run(["nvidia-smi", "--query-gpu=name,driver_version,memory.total", "--format=csv,noheader"],
                       capture_output=True, text=True, env=env)
    return q.stdout.strip().splitlines()[0] if q.returncode == 0 and q.stdout.strip() else "nvidia-smi: " + q.stderr.strip()


def host_cpu():
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip() + f", {os.cpu_count()} logical cores"
    except OSError:
        pass
    return f"{os.cpu_count()} logical cores"


def records_folder(given, pkg):
    for candidate in [given, pkg and Path(pkg) / "records" / "paper", os.environ.get("PCRF_RECORDS_DIR") and
                      Path(os.environ["PCRF_RECORDS_DIR"]) / "paper",
                      Path(__file__).resolve().parents[3] / "shared" / "records" / "paper"]:
        if candidate and all((Path(candidate) / f).is_file() for f in RECORDS.values()):
            return Path(candidate).resolve()
    return None


INTEGRATOR = ["dopri5"]  # --integrator: the one every backend of a run steps (the case kernel's)


def write_study(folder, scene, record_file, samples, pga_g, name):
    text = STUDY.format(name=name, samples=samples, record=record_file, integrator=INTEGRATOR[0]) + SCENES[scene].format(pga_g=f"{pga_g:.6f}")
    path = folder / f"{name}.toml"
    path.write_text(text)
    return path


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--pkg", help="the folder bench/gpu/package.sh made (its env.sh, bin/, records/)")
    p.add_argument("--bin", help="folder of pcrf and pcrf_gpu_bench (default: the package's bin, else build/)")
    p.add_argument("--out", default=os.environ.get("OUT") or "gpu-out", help="where the table and raw lines go")
    p.add_argument("--records", help="folder with ER1_MUL279.AT2 and ER7_CAP000.AT2")
    p.add_argument("--cases", type=int, default=1_000_000, help="cases of each scene x record")
    p.add_argument("--study-cases", type=int, default=10_000_000, help="cases of the whole study through the cube")
    p.add_argument("--cpu-ranks", type=int, default=16)
    p.add_argument("--cpu-seconds", type=float, default=15.0, help="solve time each CPU process spends at most [s]")
    p.add_argument("--gpu-seconds", type=float, default=30.0, help="solve time the GPU spends at most per workload [s]")
    p.add_argument("--study-ranks", type=int, default=4, help="ranks of the whole study (sharing the GPU)")
    p.add_argument("--budget-s", type=float, default=345.0, help="the whole run's time [s]")
    p.add_argument("--backend", default="gpu", choices=["gpu", "host-kernel"], help="what the GPU column runs")
    p.add_argument("--integrator", default="dopri5",
                   help="the balanced preset with this integrator, on every backend (the case kernel steps dopri5)")
    p.add_argument("--smoke", action="store_true", help="tiny sizes on this machine's host path")
    a = p.parse_args()
    a.pkg = str(Path(a.pkg).resolve()) if a.pkg else None
    INTEGRATOR[0] = a.integrator
    clock = Clock(a.budget_s)
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "gpu_log.txt").write_text("")
    if a.smoke:
        a.cases, a.study_cases, a.cpu_ranks, a.study_ranks = min(a.cases, 3000), min(a.study_cases, 20000), 2, 1
        a.cpu_seconds, a.gpu_seconds = min(a.cpu_seconds, 3.0), min(a.gpu_seconds, 3.0)
    root = Path(__file__).resolve().parents[2]
    env = environment(a.pkg)
    bin_dir = Path(a.bin) if a.bin else (Path(a.pkg) / "bin" if a.pkg else None)
    hook = root / "bench" / "gpu" / "build_cuda.sh"
    if hook.is_file():
        code, stdout, _, _ = run(["bash", hook], env, clock.limit(150), out)
        for line in stdout.splitlines():
            if line.startswith("PCRF_BIN_DIR="):
                bin_dir = Path(line.split("=", 1)[1].strip())
        log(f"build_cuda.sh: exit {code}", out)
    pcrf = bin_dir / "pcrf" if bin_dir else root / "build" / "pcrf"
    bench = bin_dir / "pcrf_gpu_bench" if bin_dir else root / "build" / "bench" / "gpu" / "pcrf_gpu_bench"
    records = records_folder(a.records, a.pkg)
    if records is None:
        log("gpu_measure: ER1_MUL279.AT2 and ER7_CAP000.AT2 not found (--records); nothing measured", out)
        return 1
    device = device_name(env)
    log(f"device: {device}; host: {host_cpu()}", out)
    raw = open(out / "gpu_raw.jsonl", "w")
    backend = a.backend
    probe = json_lines(run([bench, write_study(Path(tempfile.mkdtemp()), "block", records / RECORDS["ER1"], 10, 0.4,
                                               "probe"), "--backend", backend, "--cases", "10"],
                           env, clock.limit(60), out)[1])
    stand_in = ""
    if probe and "unavailable" in probe[0]:
        log(f"gpu: unavailable: {probe[0]['unavailable']}", out)
        if not a.smoke:
            log("gpu_measure: no usable GPU; the CPU rows alone are measured", out)
        backend = "host-kernel" if a.smoke else None
        stand_in = " (host build of the kernel standing in: no GPU here)" if a.smoke else ""
    rows = []
    work = Path(tempfile.mkdtemp(prefix="gpu_measure_"))
    for scene in ("block", "frame"):
        threshold = json_lines(run([bench, write_study(work, scene, records / RECORDS["ER1"], min(a.cases, 20000), 1.0,
                                                       f"{scene}_threshold"), "--median-threshold-g"],
                                   env, clock.limit(60), out)[1])
        if not threshold:
            log(f"gpu_measure: {scene}: no uplift threshold (see the stderr above); scene skipped", out)
            continue
        pga_g = 2.0 * threshold[0]["median_uplift_threshold_g"]
        for label, record in RECORDS.items():
            study = write_study(work, scene, records / record, a.cases, pga_g, f"{scene}_{label}")
            row = {"workload": f"{scene}, {label} at 2x threshold (PGA {pga_g:.3f} g)", "cases": a.cases}
            if backend:
                code, stdout, _, wall = run([bench, study, "--backend", backend, "--cases", a.cases,
                                             "--seconds-limit", a.gpu_seconds], env, clock.limit(a.gpu_seconds + 60), out)
                for j in json_lines(stdout):
                    raw.write(json.dumps(dict(j, workload=row["workload"])) + "\n")
                    row["gpu"] = j
            code, stdout, _, wall = run(["mpirun", "--oversubscribe", "-n", a.cpu_ranks, bench, study, "--backend", "cpu",
                                         "--cases", a.cases, "--group", 1024, "--seconds-limit", a.cpu_seconds],
                                        env, clock.limit(a.cpu_seconds + 90), out)
            cpu = json_lines(stdout)
            for j in cpu:
                raw.write(json.dumps(dict(j, workload=row["workload"])) + "\n")
            if cpu:
                row["cpu"] = {"cases": sum(j["cases"] for j in cpu), "ranks": len(cpu),
                              "cases_per_s": sum(j["cases_per_s"] for j in cpu)}
            rows.append(row)
            raw.flush()

    # The kernel at the group a rank gets when it is handed one whole cube chunk (16 384 cases):
    # what the study below may run at, where chunks are handed out whole.
    chunk_row = None
    if backend and (work / "block_ER1.toml").is_file():
        code, stdout, _, _ = run([bench, work / "block_ER1.toml", "--backend", backend, "--cases", a.cases, "--group", 16384,
                                  "--seconds-limit", min(a.gpu_seconds, 15.0)], env, clock.limit(75), out)
        for j in json_lines(stdout):
            raw.write(json.dumps(dict(j, workload="block, ER1, groups of 16384")) + "\n")
            chunk_row = j

    # The whole study through the cube.
    study_row = None
    block = json_lines(run([bench, work / "block_threshold.toml", "--median-threshold-g"], env, clock.limit(60), out)[1])
    pga_block = 2.0 * block[0]["median_uplift_threshold_g"] if block else 0.4
    study = write_study(work, "block", records / RECORDS["ER1"], a.study_cases, pga_block, "study_block_ER1")
    device_flag = "gpu" if backend == "gpu" else "cpu"
    cube = work / "study.h5"
    launcher = ["mpirun", "--oversubscribe", "-n", a.study_ranks] if a.study_ranks > 1 else []
    code, stdout, stderr, wall = run(launcher + [pcrf, "study", study, "-o", cube, "--device", device_flag,
                                                 "--progress-interval", "10", "--overwrite"],
                                     env, clock.limit(clock.left()), out, stop_signal=signal.SIGTERM)
    saved = a.study_cases if code == 0 else None
    m = re.search(r"(\d+) of (\d+) cases saved", stderr)
    if m:
        saved = int(m.group(1))
    study_row = {"cases": saved, "of": a.study_cases, "wall_s": wall, "code": code, "device": device_flag,
                 "ranks": a.study_ranks}
    raw.write(json.dumps({"study": study_row}) + "\n")
    raw.close()
    shutil.rmtree(work, ignore_errors=True)

    # The table.
    commit = (Path(a.pkg) / "COMMIT").read_text().strip() if a.pkg and (Path(a.pkg) / "COMMIT").is_file() else "this checkout"
    lines = [f"GPU measurement: {device}; host: {host_cpu()}; build {commit}; "
             f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}{' (smoke: tiny sizes)' if a.smoke else ''}; "
             f"balanced preset, integrator {a.integrator}, on every backend",
             "",
             f"| workload | GPU cases/s{stand_in} | GPU cases (of) | {a.cpu_ranks} cores, CPU engine: cases/s | "
             "ratio GPU / cores | GPU statuses |",
             "|---|---|---|---|---|---|"]
    for r in rows:
        g, c = r.get("gpu"), r.get("cpu")
        if g:  # a refused case is no case of the kernel's (a study gives it to the CPU engine)
            refused = g["statuses"].get("refused", 0)
            g["cases_per_s"] = (g["cases"] - refused) / g["solve_s"] if g["solve_s"] > 0 and refused < g["cases"] else 0.0
            if refused == g["cases"]:
                g = None
        gpu_rate = f"{g['cases_per_s']:,.0f}" if g else "not measured" + (" (every case refused)" if r.get("gpu") else "")
        cpu_rate = f"{c['cases_per_s']:,.0f} ({c['cases']:,} cases)" if c else "not measured"
        ratio = f"{g['cases_per_s'] / c['cases_per_s']:.1f}x" if g and c and c["cases_per_s"] > 0 else "-"
        statuses = ", ".join(f"{k} {v}" for k, v in g["statuses"].items()) if g else "-"
        lines.append(f"| {r['workload']} | {gpu_rate} | {g['cases']:,} ({r['cases']:,}) | {cpu_rate} | {ratio} | {statuses} |"
                     if g else f"| {r['workload']} | {gpu_rate} | - | {cpu_rate} | {ratio} | - |")
    if chunk_row and chunk_row["cases"] > chunk_row["statuses"].get("refused", 0):
        rate = (chunk_row["cases"] - chunk_row["statuses"].get("refused", 0)) / max(chunk_row["solve_s"], 1e-9)
        lines.append(f"| block, ER1, groups of 16 384 (one cube chunk) | {rate:,.0f} | {chunk_row['cases']:,} | | | |")
    kernel = next((r["gpu"]["cases_per_s"] for r in rows
                   if r.get("gpu") and r["gpu"]["cases_per_s"] > 0 and r["workload"].startswith("block, ER1")), None)
    if study_row["cases"]:
        rate = study_row["cases"] / study_row["wall_s"]
        versus = f"{rate / kernel:.2f}x the kernel's block/ER1 rate" if kernel else "-"
        state = "complete" if study_row["code"] == 0 else f"stopped at its time limit, {study_row['cases']:,} saved"
        lines.append(f"| whole `pcrf study --device {device_flag}` of {a.study_cases:,} blocks under ER1 through the cube, "
                     f"{a.study_ranks} rank(s) ({state}) | {rate:,.0f} (wall {study_row['wall_s']:.1f} s) | | | {versus} | |")
    else:
        lines.append(f"| whole `pcrf study` of {a.study_cases:,} blocks: failed (exit {study_row['code']}) | | | | | |")
    table = "\n".join(lines)
    print("\n" + table)
    (out / "gpu_table.md").write_text(table + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
