"""One voice: Python says what the command line says, as Python says it.

- every note and warning the command line prints on stderr is a ``warnings.warn`` of
  ``pcrf.PcrfWarning`` with the same text (each scenario below runs both), and a scan of the
  sources keeps the list of the command line's stderr lines complete;
- ``pcrf.study(..., ranks>1)`` raises what ``ranks=1`` raises, and warns what it warns;
- an error names the keyword in Python and the flag on the command line;
- containers that hold themselves or nest without end, and ints beyond 64 bits, are an
  ``InputError`` naming the key, never a crash (issue 41, items 2, 4 and 9).
"""

import re
import subprocess
import sys
import warnings
from pathlib import Path

import pytest

import pcrf
from conftest import SOURCE_DIR, cli

STUDY_TOML = """[study]
name = "voice"

[[records]]
synthetic = ["sine:amplitude_g=1.5,period_s=0.5,cycles=2,duration_s=2", "stochastic:seed=1,pga_g=1.4,duration_s=3"]

[axes]
scale = [1.0, 4.0]
kappa = [1.2, 2.4]

[physics]
tail_s = 0.05
"""

HAZARD = "pga_g,annual_rate_per_yr\n0.05,0.178885\n0.1,0.0316228\n0.3,0.00202837\n1,0.0001\n3,6.415e-06\n"


def said(stderr, prefix):
    """The command line's stderr lines after `prefix` ("pcrf study: note: "), without it."""
    return [line[len(prefix):] for line in stderr.splitlines() if line.startswith(prefix)]


def warned(call, category=pcrf.PcrfWarning):
    """(what `call()` returned, the messages of the `category` warnings it raised)."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = call()
    return result, [str(w.message) for w in caught if issubclass(w.category, category)]


@pytest.fixture(scope="module")
def unresolved(tmp_path_factory):
    """A study whose short tail leaves cases rocking (verdict notes), run by the command line;
    (study file, its cube, the command line's stderr)."""
    folder = tmp_path_factory.mktemp("voice")
    study = folder / "voice.toml"
    study.write_text(STUDY_TOML)
    _, _, stderr = cli("study", study, "-o", folder / "cli.h5")
    return study, folder / "cli.h5", stderr


@pytest.fixture(scope="module")
def ida_cube(tmp_path_factory):
    folder = tmp_path_factory.mktemp("voice_risk")
    records = [f"stochastic:seed={s},pga_g=1,duration_s=6" for s in range(1, 5)]
    study = {"study": {"name": "risk"}, "records": [{"synthetic": records}],
             "intensity": {"measure": "pga_g"}, "ida": {"start": 0.5, "max_intensity": 8.0}}
    cube = folder / "ida.h5"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", pcrf.PcrfWarning)
        pcrf.study(study, output=cube)
    (folder / "hazard.csv").write_text(HAZARD)
    return cube, folder / "hazard.csv"


# ---- every warning the command line prints, warned in Python --------------------------------

def test_a_studys_notes_are_warned_as_the_command_line_prints_them(unresolved, tmp_path):
    study, _, stderr = unresolved
    expected = said(stderr, "pcrf study: note: ")
    assert any("still rocking" in line for line in expected), stderr  # the scenario has verdict notes
    _, messages = warned(lambda: pcrf.study(study, output=tmp_path / "py.h5"))
    assert messages == expected


def test_a_cube_reports_notes_and_warnings_are_warned(unresolved):
    _, cube, _ = unresolved
    _, _, stderr = cli("cube", "stats", cube, "--by", "kappa", "-m", "theta_max_rad")
    expected = said(stderr, "pcrf cube stats: ")
    assert expected, stderr
    frame, messages = warned(lambda: pcrf.stats(cube, by="kappa", metric="theta_max_rad"))
    assert messages == expected
    assert len(frame) == 2


def test_risk_warns_what_cube_risk_prints(ida_cube):
    cube, hazard = ida_cube
    _, _, stderr = cli("cube", "risk", cube, "--hazard", hazard)
    expected = said(stderr, "pcrf cube risk: warning: ") + said(stderr, "pcrf cube risk: ")
    assert said(stderr, "pcrf cube risk: warning: "), stderr  # 4 records: the report has caveats
    frame, messages = warned(lambda: pcrf.risk(cube, hazard))
    assert sorted(messages) == sorted(line for line in expected if not line.startswith("warning: "))
    assert frame.attrs["warnings"] == said(stderr, "pcrf cube risk: warning: ")  # kept in attrs too


def test_fragility_and_p695_warn_what_they_print(ida_cube):
    cube, _ = ida_cube
    for kind, call, arguments in (("fragility", lambda: pcrf.fragility(cube), []),
                                  ("p695", lambda: pcrf.p695(cube, period_s=0.5), ["--period-s", "0.5"])):
        _, _, stderr = cli("cube", kind, cube, *arguments)
        lines = [line.removeprefix("warning: ") for line in said(stderr, f"pcrf cube {kind}: ")]
        _, messages = warned(call)
        assert messages == lines, kind


def test_open_cube_warns_what_cube_info_prints(unresolved):
    _, cube, _ = unresolved
    _, _, stderr = cli("cube", "info", cube)
    expected = said(stderr, "pcrf cube info: ")
    assert expected, stderr
    _, messages = warned(lambda: pcrf.open_cube(cube).close())
    assert messages == expected


def test_run_warns_its_notes(tmp_path):
    motion = "sine:amplitude_g=1.5,period_s=0.5,cycles=2,duration_s=2"
    _, _, stderr = cli("run", "--synthetic", motion, "--tail-s", "0.05")
    expected = said(stderr, "pcrf run: note: ")
    assert expected, stderr
    _, messages = warned(lambda: pcrf.run(synthetic=motion, tail_s=0.05))
    assert messages == expected


# The command line's stderr lines, by source file and the literal each starts with (None: a
# line made elsewhere), with how many write it, and where Python says each. A new stderr line
# changes a count: say it in Python (a PcrfWarning, or an exception for an error), add a
# scenario above, and count it here.
STDERR_LINES = {
    ("src/cli/run_command.cpp", "pcrf run: note: "): (2, "pcrf.run: PcrfWarning (test_run_warns_its_notes)"),
    ("src/cli/run_command.cpp", "pcrf run: warning: "): (2, "pcrf.run: RecordWarning (test_record_checks.py)"),
    ("src/cli/record_command.cpp", "pcrf record: note: "): (1, "pcrf.record_measures: PcrfWarning"),
    ("src/cli/record_command.cpp", "pcrf record: warning: "): (1, "pcrf.record_measures: RecordWarning (test_record_checks.py)"),
    ("src/cli/record_command.cpp", "pcrf record pulse: note: "): (1, "pcrf.pulse: PcrfWarning (its record's notes)"),
    ("src/cli/record_library_commands.cpp", "pcrf record spectra: note: "): (1, "pcrf.record_spectra: PcrfWarning"),
    ("src/cli/record_library_commands.cpp", None): (1, "record spectra's progress on a terminal: the command line's alone"),
    ("src/cli/record_library_commands.cpp", "pcrf record spectra: "): (2, "its progress and its count of components: "
                                                                         "the command line's; Python returns the table"),
    ("src/cli/record_library_commands.cpp", "pcrf record select: largest error of the median "): (
        1, "the fit's errors: pcrf.select returns them (median_error_percent, sigma_error_percent)"),
    ("src/cli/study_command.cpp", None): (2, "its error lines: raised (test_more_ranks_raise_what_one_rank_raises)"),
    ("src/cli/study_command.cpp", "pcrf: error: "): (1, "an internal error on a rank: RuntimeError"),
    ("src/cli/study_command.cpp", "pcrf study: "): (1, "the stop report: a note of the KeyboardInterrupt"),
    ("src/cli/study_command.cpp", "pcrf study: note: "): (1, "verdict notes: PcrfWarning (test_a_studys_notes_…)"),
    ("src/run/study_run.cpp", "pcrf study: note: "): (1, "the study's notes: StudyRunOptions::notes, PcrfWarning"),
    ("src/run/study_run.cpp", "pcrf study: note: rank "): (1, "a worker rank's GPU refusals: a note line, PcrfWarning under mpirun"),
    ("src/run/study_run.cpp", "pcrf study: warning: "): (1, "record checks: RecordWarning (test_record_checks.py)"),
    ("src/run/study_run.cpp", "pcrf: error on rank "): (1, "an internal error on a rank: RuntimeError"),
    ("src/run/progress.cpp", "pcrf study: "): (2, "progress lines: printed with progress=True"),
    ("src/cli/cube_command.cpp", "pcrf cube: "): (1, "running_note: PcrfWarning of open_cube and the reports"),
    ("src/cli/cube_command.cpp", "pcrf cube "): (2, "report notes and warnings: PcrfWarning (test_…_warn…)"),
    ("src/cli/cube_command.cpp", "pcrf cube info: "): (2, "open_cube: PcrfWarning (test_open_cube_warns_…)"),
    ("src/cli/cube_command.cpp", None): (1, "cube info --json's curve states: the cube's curve_state variable"),
    ("src/cli/cube_command.cpp", "pcrf cube merge: "): (1, "the command line's alone: Python has no merge"),
    ("src/cli/main.cpp", None): (1, "the error line: InputError, OutputError, RuntimeError"),
    ("src/cli/main.cpp", "pcrf: error: "): (1, "help or version not written: the command line's alone"),
}
STDERR_WRITE = re.compile(r"std::cerr\s*(?:<<|:)|\bprogress\s*<<|\bout_\s*<<\s*\"pcrf")


def stderr_lines_in_sources():
    found = {}
    for path in sorted((SOURCE_DIR / "src").rglob("*.cpp")):
        relative = path.relative_to(SOURCE_DIR).as_posix()
        if relative.startswith("src/python/"):
            continue
        for line in path.read_text(encoding="utf-8").splitlines():
            if line.lstrip().startswith("//") or not STDERR_WRITE.search(line):
                continue
            literal = re.search(r'"((?:[^"\\]|\\.)*)"', line[STDERR_WRITE.search(line).start():])
            key = (relative, literal.group(1) if literal and literal.group(1).startswith("pcrf") else None)
            found[key] = found.get(key, 0) + 1
    return found


def test_every_stderr_line_of_the_command_line_has_its_python_voice():
    found = stderr_lines_in_sources()
    expected = {key: count for key, (count, _) in STDERR_LINES.items()}
    new = {key: count for key, count in found.items() if expected.get(key) != count}
    gone = {key: count for key, count in expected.items() if key not in found}
    assert not new and not gone, (f"stderr lines not accounted for in Python (say them as a PcrfWarning or raise "
                                  f"them, then count them in STDERR_LINES): {new}; listed but gone: {gone}")


# ---- ranks > 1 raise and warn as ranks = 1 ---------------------------------------------------

def test_more_ranks_raise_what_one_rank_raises(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    bad = {"records": [{"synthetic": ["sine:amplitude_g=1,period_s=0.5"]}], "axes": {"kappa": [1.2]},
           "physics": {"tail_s": -1.0}}
    raised = []
    for ranks in (1, 2):
        with pytest.raises(pcrf.InputError) as error:
            pcrf.study(bad, output=tmp_path / f"bad{ranks}.h5", ranks=ranks)
        raised.append((str(error.value), error.value.key))
    assert raised[0] == raised[1]
    assert raised[0][1] == "tail_s"
    # A [run] keyword is checked in process too, named as a keyword.
    good = dict(bad, physics={"tail_s": 0.5})
    for ranks in (1, 2):
        with pytest.raises(pcrf.InputError, match="flush_interval_s=") as error:
            pcrf.study(good, output=tmp_path / "bad.h5", ranks=ranks, flush_interval_s=-5)
        assert error.value.key == "flush_interval_s"
    # An output that exists: the same refusal, naming the keywords.
    (tmp_path / "there.h5").write_text("")
    messages = []
    for ranks in (1, 2):
        with pytest.raises(pcrf.InputError) as error:
            pcrf.study(good, output=tmp_path / "there.h5", ranks=ranks)
        messages.append(str(error.value))
    assert messages[0] == messages[1]
    assert "resume" in messages[0] and "--" not in messages[0]


def test_more_ranks_warn_what_one_rank_warns(unresolved, tmp_path):
    study, _, _ = unresolved
    _, one = warned(lambda: pcrf.study(study, output=tmp_path / "one.h5"))
    _, two = warned(lambda: pcrf.study(study, output=tmp_path / "two.h5", ranks=2))
    assert one and one == two


# ---- errors name the keyword in Python, the flag on the command line --------------------------

def test_a_post_processing_error_names_the_keyword(unresolved):
    _, cube, _ = unresolved
    with pytest.raises(pcrf.InputError, match=r"group by \(by=\)") as error:
        pcrf.stats(cube, by=[], metric="theta_max_rad")
    assert "--by" not in str(error.value)
    with pytest.raises(pcrf.InputError, match="reduce_over= needs an IDA cube"):
        pcrf.fragility(cube, reduce_over="kappa")
    code, _, stderr = cli("cube", "fragility", cube, "--reduce-over", "kappa", check=False)
    assert code == 2 and "--reduce-over needs an IDA cube" in stderr
    with pytest.raises(pcrf.InputError, match="by=: expected a string or a list of strings"):
        pcrf.stats(cube, by=[1], metric="theta_max_rad")


# ---- containers and integers: InputError naming the key, never a crash -----------------------

def nested(depth):
    value = []
    for _ in range(depth):
        value = [value]
    return value


def holding_itself():
    d = {"from": 1.0}
    d["to"] = d
    return d


@pytest.mark.parametrize("value, problem", [(nested(200_000), "nests lists and dicts more than 32 deep"),
                                            (holding_itself(), "holds itself")])
def test_a_study_of_containers_without_end_is_refused_naming_the_key(value, problem):
    with pytest.raises(pcrf.InputError, match=re.escape(problem)) as error:
        pcrf.study({"axes": {"kappa": value}}, output="never.h5")
    assert error.value.key in ("kappa", "to")
    assert str(error.value).startswith("study: [axes] kappa")
    cyclic = {}
    cyclic["axes"] = cyclic
    with pytest.raises(pcrf.InputError, match="axes: holds itself"):
        pcrf.study(cyclic, output="never.h5")


def test_a_study_source_that_is_neither_a_dict_nor_a_path_is_refused():
    for source in (nested(200_000), 42, holding_itself()["to"].keys()):
        with pytest.raises(pcrf.InputError, match="source=: expected a dict") as error:
            pcrf.study(source, output="never.h5")
        assert error.value.key == "source"


@pytest.mark.parametrize("keywords, key", [
    ({"frame": {"kappa": nested(200_000)}}, "kappa"),
    ({"tail_s": nested(200_000)}, "tail_s"),
    ({"outputs": holding_itself()}, "to"),
])
def test_every_keyword_taking_containers_is_bounded(keywords, key):
    with pytest.raises(pcrf.InputError) as error:
        pcrf.run(synthetic="sine:amplitude_g=1,period_s=0.5", **keywords)
    assert error.value.key == key


def test_containers_in_a_report_keyword_are_bounded(unresolved):
    _, cube, _ = unresolved
    looped = ["kappa"]
    looped.append(looped)
    with pytest.raises(pcrf.InputError, match=r"by\[1\]: holds itself"):
        pcrf.stats(cube, by=looped, metric="theta_max_rad")


def test_the_depth_bound_is_documented():
    assert "32" in (SOURCE_DIR / "docs" / "python.md").read_text(encoding="utf-8").split("nest")[1][:400]


@pytest.mark.parametrize("call, key, says", [
    (lambda: pcrf.run(synthetic="sine:amplitude_g=1,period_s=0.5", max_steps=2**70), "max_steps", "out of range"),
    (lambda: pcrf.study({"physics": {"max_steps": 2**70}}, output="never.h5"), "max_steps", "out of range"),
    # points: the pushover's own bound (api::pushover_points, shared with `pcrf frame --points`)
    (lambda: pcrf.Frame(points=2**70), "points", "must be at most 100000"),
    (lambda: pcrf.run(record="never.txt", format="one-column", dt_s=0.01, skip_rows=2**70), "skip_rows", "out of range"),
    (lambda: pcrf.run(synthetic="sine:amplitude_g=1,period_s=0.5", tail_s=10**400), "tail_s", "out of range"),
])
def test_an_int_out_of_range_names_its_key(call, key, says):
    with pytest.raises(pcrf.InputError, match=says) as error:
        call()
    assert error.value.key == key
    assert "Unable to cast" not in str(error.value)


def test_an_int_that_fits_a_number_setting_is_the_setting_to_check(tmp_path):
    with pytest.raises(pcrf.InputError, match="tail_s=") as error:
        pcrf.run(synthetic="sine:amplitude_g=1,period_s=0.5", tail_s=-(2**70))
    assert "out of range" not in str(error.value)  # a number: -1.18e21, refused as any negative tail


# ---- import pcrf gives everything; pcrf plot's kinds come from one table ------------------------

def test_import_pcrf_gives_pcrf_plot():
    done = subprocess.run([sys.executable, "-c", "import pcrf; print(pcrf.plot.figure.__name__)"],
                          capture_output=True, text=True)
    assert done.returncode == 0 and done.stdout.strip() == "figure", done.stderr


def test_pcrf_plot_help_lists_the_kinds_of_the_one_table():
    from pcrf.plot.cli import KINDS

    _, help_text, _ = cli("--help")
    line = next(line for line in help_text.splitlines() if line.strip().startswith("plot "))
    assert re.search(r"kinds: ([^;]*);", line).group(1).split(", ") == list(KINDS)
    assert "risk" in KINDS
    modules = {p.stem for p in (Path(pcrf.plot.__file__).parent).glob("*.py")
               if "def draw(" in p.read_text(encoding="utf-8")}
    assert modules == set(KINDS)


# ---- the docs' rules are the engine's -------------------------------------------------------

def test_the_ida_run_rule_is_stated_once_and_rendered_as_checked(tmp_path):
    _, table, _ = cli("settings")
    row = next(line for line in table.splitlines() if line.startswith("| `max_runs` |"))
    least = int(re.search(r"integer ≥ (\d+)", row).group(1))
    readme = (SOURCE_DIR / "studies" / "README.md").read_text(encoding="utf-8")
    assert row in readme
    study = {"records": [{"synthetic": ["sine:amplitude_g=1,period_s=0.5"]}], "intensity": {"measure": "pga_g"},
             "ida": {"start": 0.5, "max_intensity": 8.0, "max_runs": least - 1}}
    with pytest.raises(pcrf.InputError, match=f"max_runs: must be at least {least}"):
        pcrf._pcrf.study_text(study)
    study["ida"]["max_runs"] = least
    assert "max_runs" in pcrf._pcrf.study_text(study)
