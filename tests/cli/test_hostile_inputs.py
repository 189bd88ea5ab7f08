"""Hostile and bad inputs across every command (issue 16), table-driven.

Each case of ``tests/data/hostile_inputs.toml`` runs the real entry point in-process
(`sloshkit.cli.app.run`, the function `main` exits with) in a folder of fixture files and must
end with its exit code, exactly one ``error:`` line on stderr that names the parameter, nothing
on stdout, no traceback, and the folder unchanged (no file created, modified or removed; no
staging folder left behind).
"""

from __future__ import annotations

import math
import os
import stat
import subprocess
import tomllib
from pathlib import Path

import numpy as np
import pytest
from hostile_fixtures import make_spatial_fixtures

from sloshkit.cli import load_commands
from sloshkit.cli.app import run
from sloshkit.io.models import write_model_file
from sloshkit.model import UprightCylinder, equivalent_model, get_liquid

load_commands()  # the entry point imports only the command it runs; the tests run them all

TABLE = Path(__file__).parents[1] / "data" / "hostile_inputs.toml"
CASES = tomllib.loads(TABLE.read_text(encoding="utf-8"))["case"]

SCENARIO = """\
name = "hostile base"
analyses = ["model", "compare"]

[container]
radius = "20.5mm"
wall_height = "60mm"

[liquid]
preset = "water-25C"

[fill]
height = "39mm"

[model]
modes = 3

[move]
distance = "0.5m"
peak_velocity = "0.5m/s"
laws = ["quintic"]
"""

PLAN_LIMITS = """
[limits]
max_angle = "5deg"
max_residual = "0.25deg"
vmax = "1.5m/s"
amax = "20m/s^2"
jmax = "500m/s^3"
"""

#: Scenario variants: (text to replace, replacement, extra text appended).
SCENARIOS: dict[str, tuple[str, str, str]] = {
    "ok": ("", "", ""),
    "radius_bool": ('radius = "20.5mm"', "radius = true", ""),
    "radius_list": ('radius = "20.5mm"', "radius = [1, 2]", ""),
    "radius_comma": ('radius = "20.5mm"', 'radius = "20,5mm"', ""),
    "radius_arithmetic": ('radius = "20.5mm"', 'radius = "9**9**9 m"', ""),
    "radius_table": ('radius = "20.5mm"', "radius = { value = 1 }", ""),
    "modes_text": ("modes = 3", 'modes = "three"', ""),
    "modes_float": ("modes = 3", "modes = 2.5", ""),
    "modes_bool": ("modes = 3", "modes = true", ""),
    "robust_text": (
        'analyses = ["model", "compare"]',
        'analyses = ["plan"]',
        PLAN_LIMITS.replace('jmax = "500m/s^3"', 'jmax = "500m/s^3"\nrobust = "abc"'),
    ),
    "laws_text": ('laws = ["quintic"]', 'laws = "quintic"', ""),
    "laws_numbers": ('laws = ["quintic"]', "laws = [1, 2]", ""),
    "analyses_text": ('analyses = ["model", "compare"]', 'analyses = "model"', ""),
    "analyses_unknown": ('analyses = ["model", "compare"]', 'analyses = ["model", "magic"]', ""),
    "unknown_key": ('radius = "20.5mm"', 'radius = "20.5mm"\nradiuss = "1mm"', ""),
    "unknown_table": ("", "", '\n[containr]\nradius = "1mm"\n'),
    "markup_key": ('radius = "20.5mm"', 'radius = "20.5mm"\n"[/red]" = 1', ""),
    "no_radius": ('radius = "20.5mm"\n', "", ""),
    "fill_both": ('height = "39mm"', 'height = "39mm"\nvolume = "2mL"', ""),
    "preset_number": ('preset = "water-25C"', "preset = 5", ""),
    "damping_law_unknown": ("modes = 3", 'modes = 3\ndamping_law = "magic"', ""),
    "damping_ratio_text": ("modes = 3", 'modes = 3\ndamping_ratio = "abc"', ""),
    "sweep_count_huge": (
        'analyses = ["model", "compare"]',
        'analyses = ["sweep"]',
        '\n[limits]\nmax_angle = "5deg"\nmax_residual = "1deg"\n'
        '\n[sweep]\nfill_height = "10mm:50mm:99999999999"\n',
    ),
    "sweep_laws_text": (
        'analyses = ["model", "compare"]',
        'analyses = ["sweep"]',
        '\n[limits]\nmax_angle = "5deg"\nmax_residual = "1deg"\n\n[sweep]\nlaws = "quintic"\n',
    ),
    "surface_tension_text": ("modes = 3", 'modes = 3\nsurface_tension_correction = "yes"', ""),
    "paper_comparison_text": ('name = "hostile base"', 'name = "x"\npaper_comparison = "yes"', ""),
    "container_not_table": ("[container]\n", "container = 5\n[containerx]\n", ""),
    "limits_missing": ('analyses = ["model", "compare"]', 'analyses = ["plan"]', ""),
    "sample_period_text": (
        'analyses = ["model", "compare"]',
        'analyses = ["plan"]',
        PLAN_LIMITS + 'sample_period = "fast"\n',
    ),
    "density_negative": ('preset = "water-25C"', 'preset = "water-25C"\ndensity = "-1kg/m^3"', ""),
    "name_table": ('name = "hostile base"', "name = { a = 1 }", ""),
}


def _model_document_variants(folder: Path) -> None:
    """Valid model file, then broken copies (NaN, negative, wrong types, no modes)."""
    model = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039)
    good = write_model_file(folder / "good_model.toml", model).read_text()
    lines = good.splitlines()

    def replaced(prefix: str, new: str, first_only: bool = True) -> str:
        out, done = [], False
        for line in lines:
            if line.startswith(prefix) and not (done and first_only):
                out.append(new)
                done = True
            else:
                out.append(line)
        return "\n".join(out) + "\n"

    omega = next(line for line in lines if line.startswith("omega_rad_s"))
    variants = {
        "nan_model.toml": replaced("omega_rad_s", "omega_rad_s = nan"),
        "negative_model.toml": replaced("omega_rad_s", "omega_rad_s = -" + omega.split("= ")[1]),
        "negative_hz_model.toml": replaced("frequency_hz", "frequency_hz = -1.0"),
        "text_radius_model.toml": replaced("radius_m", 'radius_m = "20mm"'),
        "bool_radius_model.toml": replaced("radius_m", "radius_m = true"),
        "overdamped_model.toml": replaced("damping_ratio", "damping_ratio = 1.5"),
        "no_modes_model.toml": "\n".join(line for line in good.split("[[modes]]")[0].splitlines())
        + "\n",
    }
    for name, text in variants.items():
        (folder / name).write_text(text, encoding="utf-8")


def _decay_csv() -> str:
    t = np.arange(0.0, 6.0, 0.005)
    eta = 2e-3 * np.exp(-0.02 * 29.0 * t) * np.cos(29.0 * t)
    return "t,eta\n" + "".join(f"{a:.6f},{b:.9f}\n" for a, b in zip(t, eta, strict=True))


def _make_fixtures(folder: Path) -> None:
    (folder / "adir").mkdir()
    (folder / "full").mkdir()
    (folder / "full" / "user.txt").write_text("the user's own file\n")
    (folder / "afile").write_text("a plain file\n")
    (folder / "decay.csv").write_text(_decay_csv())
    (folder / "empty.csv").write_text("")
    (folder / "empty.toml").write_text("")
    (folder / "header_only.csv").write_text("t,x\n")
    (folder / "text.csv").write_text("t,x\n0,zero\n1,one\n")
    (folder / "one_column.csv").write_text("0\n1\n2\n3\n4\n5\n6\n")
    (folder / "duplicate_time.csv").write_text(
        "t,x\n0,0\n0.1,0\n0.1,0.1\n0.2,0.2\n0.3,0.3\n0.4,0.4\n"
    )
    (folder / "nan_motion.csv").write_text(
        "t,x\n0,0\n0.1,nan\n0.2,0.1\n0.3,0.2\n0.4,0.3\n0.5,0.3\n"
    )
    (folder / "short_motion.csv").write_text("t,x\n0,0\n0.1,0.1\n")
    (folder / "ragged.csv").write_text("t,x\n0,0\n0.1,0.1,7\n0.2,0.2\n")
    (folder / "binary.csv").write_bytes(bytes(range(256)) * 4)
    (folder / "binary.toml").write_bytes(b"\x00\x01\x02radius = 1\x00")
    (folder / "latin1.toml").write_bytes('name = "caf\u00e9"\n'.encode("latin-1"))
    (folder / "deep.toml").write_text("a = " + "[" * 5000 + "]" * 5000 + "\n")
    (folder / "deep.json").write_text("[" * 100000 + "]" * 100000)
    (folder / "array.json").write_text("[1, 2, 3]")
    (folder / "invalid.toml").write_text("[container\nradius = \n")
    (folder / "huge.toml").write_text("# padding\n" * 600_000)
    _model_document_variants(folder)
    make_spatial_fixtures(folder)
    for name, (old, new, extra) in SCENARIOS.items():
        text = SCENARIO.replace(old, new, 1) if old else SCENARIO
        (folder / f"s_{name}.toml").write_text(text + extra, encoding="utf-8")


def _no_process(*args: object, **kwargs: object) -> None:
    raise AssertionError(f"a hostile input started a process: {args[:1]}")


def _snapshot(folder: Path) -> dict[str, tuple[int, int, int]]:
    """Every path under ``folder`` with (size, mtime_ns, mode)."""
    state = {}
    for path in sorted(folder.rglob("*")):
        info = path.lstat()
        state[str(path.relative_to(folder))] = (
            info.st_size if not stat.S_ISDIR(info.st_mode) else 0,
            info.st_mtime_ns,
            info.st_mode,
        )
    return state


@pytest.fixture(scope="module")
def fixture_folder(tmp_path_factory: pytest.TempPathFactory) -> Path:
    folder = tmp_path_factory.mktemp("hostile")
    _make_fixtures(folder)
    return folder


def test_the_table_is_large_and_unique() -> None:
    ids = [case["id"] for case in CASES]
    assert len(ids) >= 150
    assert len(set(ids)) == len(ids)
    commands = {
        case["args"][0] if not case["args"][0].startswith("-") else case["args"][2]
        for case in CASES
    }
    assert {"model", "simulate", "compare", "sweep", "calibrate", "plan", "export", "run"} <= (
        commands
    )
    cfd = {case["args"][1] for case in CASES if case["args"][0] == "cfd"}
    assert {"run", "sweep", "validate", "analyse"} <= cfd


@pytest.mark.parametrize("case", CASES, ids=[case["id"] for case in CASES])
def test_hostile_input(
    case: dict[str, object],
    fixture_folder: Path,
    monkeypatch: pytest.MonkeyPatch,
    capsys: pytest.CaptureFixture[str],
) -> None:
    monkeypatch.chdir(fixture_folder)
    monkeypatch.delenv("SLOSHKIT_MAX_MEMORY", raising=False)
    # Every case must be refused before any work: none may start a process (interFoam, mpirun).
    monkeypatch.setattr(subprocess, "Popen", _no_process)
    before = _snapshot(fixture_folder)
    code = run([str(arg) for arg in case["args"]])  # type: ignore[attr-defined]
    captured = capsys.readouterr()
    lines = [line for line in captured.err.splitlines() if line.strip()]
    errors = [line for line in lines if line.startswith("error:")]
    assert code == case["code"], captured.err
    assert len(errors) == 1, captured.err
    assert all(line.startswith(("error:", "warning:")) for line in lines), captured.err
    named = str(case["names"])  # a Python name matches the option or argument it stands for
    spellings = {named, "--" + named.replace("_", "-"), named.upper()}
    assert any(spelling in errors[0] for spelling in spellings), errors[0]
    assert "Traceback" not in captured.err + captured.out
    assert captured.out == ""
    assert _snapshot(fixture_folder) == before
    assert stat.S_ISCHR(os.stat("/dev/null").st_mode)  # never replaced by a regular file


def test_markup_and_emoji_in_values_are_printed_literally(
    fixture_folder: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.chdir(fixture_folder)
    assert run(["model", "--liquid", "[/red] :x: [bold]b"]) == 2
    assert "'[/red] :x: [bold]b'" in capsys.readouterr().err


def test_a_bom_in_a_csv_header_is_stripped(
    fixture_folder: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    (tmp_path / "bom.csv").write_text("\ufeff" + _decay_csv(), encoding="utf-8")
    assert run(["calibrate", "bom.csv", "--time-column", "t", "--signal-column", "eta"]) == 0


def test_a_motion_file_not_ending_at_rest_warns(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.chdir(tmp_path)
    rows = "".join(f"{0.01 * k:.2f},{0.005 * k:.4f}\n" for k in range(101))
    (tmp_path / "ramp.csv").write_text("t,x\n" + rows)
    assert run(["simulate", "--law", "file:ramp.csv", "--json"]) == 0
    assert "does not end at rest" in capsys.readouterr().err


def test_replacing_a_file_keeps_its_permissions(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    target = tmp_path / "out.csv"
    target.write_text("old\n")
    target.chmod(0o600)
    assert run(["simulate", "--duration", "1.5s", "--csv", "out.csv", "--json"]) == 0
    assert stat.S_IMODE(target.stat().st_mode) == 0o600
    assert target.read_text().startswith("t_s")


def test_an_output_folder_written_by_sloshkit_may_be_rewritten(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    args = ["compare", "--laws", "quintic", "--out", "cmp", "--json"]
    assert run(args) == 0
    assert run(args) == 0  # its own marker: no --overwrite needed
    (tmp_path / "mine").mkdir()
    (tmp_path / "mine" / "notes.txt").write_text("keep")
    assert run(["compare", "--laws", "quintic", "--out", "mine", "--json"]) == 2
    assert run(["compare", "--laws", "quintic", "--out", "mine", "--json", "--overwrite"]) == 0
    assert (tmp_path / "mine" / "notes.txt").read_text() == "keep"
    assert not list(tmp_path.glob(".*staging*"))


def test_plan_falls_back_when_no_ei_shaper_exists(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.chdir(tmp_path)
    limits = ["--vmax", "1.5m/s", "--amax", "20m/s^2", "--jmax", "500m/s^3"]
    slosh = ["--max-angle", "5deg", "--max-residual", "0.25deg", "--damping-ratio", "0.34"]
    assert run(["plan", *limits, *slosh, "--method", "shaped", "--json"]) == 0
    assert "no EI shaper exists" in capsys.readouterr().err


def test_memory_limit_option_and_environment(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.setenv("SLOSHKIT_MAX_MEMORY", "1MiB")
    assert run(["simulate", "--duration", "100s"]) == 2
    assert "above the memory limit 1.0 MiB" in capsys.readouterr().err
    assert run(["--max-memory", "8GiB", "simulate", "--duration", "100s", "--json"]) == 0
    assert os.environ["SLOSHKIT_MAX_MEMORY"] == "1MiB"  # restored after the run
    assert math.isfinite(1.0)
