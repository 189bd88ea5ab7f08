"""CFD inputs of issue 30 as the process meets them: a case folder's JSON files and
function-object output (`cfd analyse`), case paths OpenFOAM refuses (checked before anything
is written, the working folder included), and ``cfd sweep --scheduler`` against servers that
are not Dask schedulers (tiny socket servers on 127.0.0.1, bounded and self-stopping)."""

from __future__ import annotations

import contextlib
import json
import math
import socket
import subprocess
import sys
import threading
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest

from sloshkit.cfd.case import SCALE, probe_columns, spec_summary
from sloshkit.cfd.prepare import check_case_path, write_case
from sloshkit.cfd.scheduler import check_scheduler, redact
from sloshkit.cfd.spec import CaseSpec
from sloshkit.errors import InputError
from sloshkit.model.liquids import get_liquid

ENTRY = [sys.executable, "-c", "from sloshkit.cli import main; main()"]


def run(*args: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [*ENTRY, *args],
        capture_output=True,
        text=True,
        cwd=cwd,
        timeout=300,  # a hang guard, not a speed test
        check=False,
    )


def one_error(result: subprocess.CompletedProcess[str], *words: str) -> str:
    assert result.returncode == 2, result.stdout + result.stderr
    lines = [line for line in result.stderr.splitlines() if line.strip()]
    assert len(lines) == 1 and lines[0].startswith("error: "), result.stderr
    assert "Traceback" not in result.stderr
    for word in words:
        assert word in lines[0], lines[0]
    return lines[0]


# -- a finished case, written without OpenFOAM -------------------------------------------------

SPEC = CaseSpec(0.0205, 0.039, get_liquid("water-25C"), cells_per_radius=4, end_time_s=2.0)


def finished_case(folder: Path, force_rows: bool = True) -> Path:
    """A case whose function objects hold a decaying first-mode slosh (4.7 Hz, zeta 0.01)."""
    case = write_case(SPEC, folder / "case")
    summary = spec_summary(SPEC)
    z, dz = probe_columns(SPEC)
    angles = np.asarray(summary["probe_angles_rad"])
    t = np.arange(0.0, SPEC.end_time_s + 1e-9, 0.002)
    omega = 2 * math.pi * 4.7
    eta = 2e-3 * np.exp(-0.01 * omega * t) * np.cos(omega * t)
    columns = []
    for angle in angles:
        height = SPEC.fill_height_m + eta * math.cos(angle)
        alpha = np.clip((height[:, None] - (z[None, :] - dz / 2)) / dz, 0.0, 1.0)
        columns.append(alpha)
    probes = np.column_stack([t, *columns])
    force = 1e-3 * eta / 2e-3 * SCALE**4

    def write(name: str, file_name: str, rows: list[str], header: str) -> None:
        target = case / "postProcessing" / name / "0" / file_name
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_text(header + "".join(rows))

    write(
        "wallProbes",
        "alpha.water",
        [" ".join(f"{v:.9g}" for v in row) + "\n" for row in probes],
        "# Time probes\n",
    )
    write(
        "surfaceTilt",
        "volFieldValue.dat",
        [f"{a:.9g} ({1e-3 * b:.9g} 0 -1)\n" for a, b in zip(t, eta, strict=True)],
        "# Time areaAverage(nHat)\n",
    )
    rows = [f"{a:.9g} ({b:.9g} 0 0) (0 0 0) (0 0 0)\n" for a, b in zip(t, force, strict=True)]
    write("wallForces", "force.dat", rows if force_rows else [], "# Time total pressure viscous\n")
    return case


def test_a_synthetic_finished_case_calibrates_from_its_wall_force(tmp_path: Path) -> None:
    case = finished_case(tmp_path)
    result = run("cfd", "analyse", str(case), "--json", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    payload = json.loads(result.stdout)
    assert payload["damping_signal"] == "wall_force"
    assert payload["frequency_hz"] == pytest.approx(4.7, rel=1e-3)


@pytest.mark.parametrize(
    ("text", "words"),
    [
        ("{not json", ("sloshkit-case.json", "is not valid JSON")),
        ("[1, 2]", ("sloshkit-case.json", "JSON object")),
        ('{"end_time_s": "3 s"}', ("sloshkit-case.json", "radius_m")),
        (None, ("sloshkit-case.json", "'end_time_s' is \"3 s\"")),
        (None, ("sloshkit-case.json", "'probes_per_column'")),
        (None, ("sloshkit-case.json", "'excitation'")),
    ],
)
def test_a_broken_case_description_is_one_line_naming_the_file(
    tmp_path: Path, text: str | None, words: tuple[str, ...]
) -> None:
    case = finished_case(tmp_path)
    summary = json.loads((case / "sloshkit-case.json").read_text())
    if text is None:  # one key of the right description given the wrong type
        key = words[1].split("'")[1]
        summary[key] = {"end_time_s": "3 s", "probes_per_column": 2.5, "excitation": 7}[key]
        text = json.dumps(summary)
    (case / "sloshkit-case.json").write_text(text)
    for command in (
        ["cfd", "analyse", str(case)],
        ["cfd", "validate", "--case", str(case), "--reuse"],
    ):
        one_error(run(*command, cwd=tmp_path), *words)


def test_a_broken_run_record_is_one_line_naming_the_file(tmp_path: Path) -> None:
    case = finished_case(tmp_path)
    (case / "sloshkit-run.json").write_text('{"wall_clock_s": "slow"}')
    one_error(run("cfd", "analyse", str(case), cwd=tmp_path), "sloshkit-run.json")


def test_nan_in_the_wall_force_is_an_error_not_a_switch_of_signal(tmp_path: Path) -> None:
    case = finished_case(tmp_path)
    force = case / "postProcessing" / "wallForces" / "0" / "force.dat"
    lines = force.read_text().splitlines(keepends=True)
    lines[200] = lines[200].split(" ", 1)[0] + " (nan 0 0) (0 0 0) (0 0 0)\n"
    force.write_text("".join(lines))
    one_error(run("cfd", "analyse", str(case), cwd=tmp_path), "force.dat", "nan", "t = 0.398")


def test_nan_in_the_probes_is_an_error(tmp_path: Path) -> None:
    case = finished_case(tmp_path)
    probes = case / "postProcessing" / "wallProbes" / "0" / "alpha.water"
    lines = probes.read_text().splitlines(keepends=True)
    parts = lines[50].split()
    lines[50] = " ".join([parts[0], "nan", *parts[2:]]) + "\n"
    probes.write_text("".join(lines))
    one_error(run("cfd", "analyse", str(case), cwd=tmp_path), "alpha.water", "nan")


def test_a_finished_case_with_a_header_only_force_file_is_calibrated_and_says_so(
    tmp_path: Path,
) -> None:
    case = finished_case(tmp_path, force_rows=False)
    result = run("cfd", "analyse", str(case), "--json", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    payload = json.loads(result.stdout)
    assert payload["damping_signal"] == "wall_elevation"
    assert any("no wall-force rows" in text for text in payload["warnings"])
    assert "no wall-force rows" in result.stderr
    assert "unfinished" not in result.stderr


# -- case paths -----------------------------------------------------------------------------


@pytest.mark.parametrize(
    "name", ["a b", "it's", 'a"b', "a$b", "a`b`", "a;b", "a\nb", "caf\u00e9", "a~b", "a\tb"]
)
def test_a_case_path_openfoam_refuses_is_refused_before_anything_is_written(
    tmp_path: Path, name: str
) -> None:
    with pytest.raises(InputError, match="OpenFOAM v1912 takes only"):
        write_case(SPEC, tmp_path / name)
    assert list(tmp_path.iterdir()) == []
    check_case_path(tmp_path / "fine-name_1.2+x=y,z@w")


def test_a_relative_case_in_a_working_folder_with_a_space_is_refused(tmp_path: Path) -> None:
    work = tmp_path / "my runs"
    work.mkdir()
    result = run("cfd", "run", "--case", "c", "--cells-per-radius", "4", cwd=work)
    line = one_error(result, "case = 'c'", "a space", "my runs")
    assert "OpenFOAM" in line
    assert list(work.iterdir()) == []
    result = run("cfd", "sweep", "--out", "camp", "--cells-per-radius", "4", cwd=work)
    one_error(result, "out = 'camp'", "a space")
    assert list(work.iterdir()) == []


# -- the scheduler handshake ----------------------------------------------------------------


@pytest.fixture
def fake_scheduler(request: pytest.FixtureRequest) -> Iterator[int]:
    """A server on 127.0.0.1 that accepts and then stays silent, or sends garbage; it stops by
    itself after 60 s at most and when the test ends."""
    mode = request.param
    server = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    server.bind(("127.0.0.1", 0))
    server.listen(8)
    server.settimeout(0.2)
    stop = threading.Event()
    accepted: list[socket.socket] = []

    def serve() -> None:
        deadline = 300  # x 0.2 s
        while not stop.is_set() and deadline > 0:
            deadline -= 1
            try:
                connection, _ = server.accept()
            except TimeoutError:
                continue
            accepted.append(connection)
            if mode == "garbage":
                with contextlib.suppress(OSError):
                    connection.sendall(bytes(range(256)) * 16)

    thread = threading.Thread(target=serve, daemon=True)
    thread.start()
    try:
        yield server.getsockname()[1]
    finally:
        stop.set()
        thread.join(timeout=5)
        for connection in accepted:
            connection.close()
        server.close()


@pytest.mark.parametrize("fake_scheduler", ["silent", "garbage"], indirect=True)
def test_a_port_that_is_not_a_dask_scheduler_is_refused_leaving_nothing(
    tmp_path: Path, fake_scheduler: int
) -> None:
    address = f"tcp://admin:hunter2@127.0.0.1:{fake_scheduler}"
    result = run("cfd", "sweep", "--out", "camp", "--scheduler", address, cwd=tmp_path)
    one_error(result, "scheduler", "***@127.0.0.1")
    assert "hunter2" not in result.stderr + result.stdout
    plain = f"tcp://127.0.0.1:{fake_scheduler}"
    result = run(
        "cfd",
        "sweep",
        "--out",
        "camp",
        "--scheduler",
        plain,
        "--cells-per-radius",
        "4",
        cwd=tmp_path,
    )
    one_error(result, f"scheduler = '{plain}'", "did not answer as a Dask scheduler")
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("fake_scheduler", ["silent"], indirect=True)
def test_the_handshake_is_bounded_by_its_timeout(fake_scheduler: int) -> None:
    with pytest.raises(InputError, match="within 1 s"):
        check_scheduler(f"127.0.0.1:{fake_scheduler}", timeout_s=1.0)


def test_a_real_dask_scheduler_passes_the_handshake() -> None:
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(
        processes=False,
        n_workers=0,
        host="127.0.0.1",
        scheduler_port=0,
        dashboard_address=None,
        protocol="tcp",
    ) as cluster:
        address = cluster.scheduler_address
        assert check_scheduler(address) == address


def test_credentials_are_redacted_wherever_they_are_written() -> None:
    assert redact("tcp://u:p@h:1") == "tcp://***@h:1"
    assert redact("u:secret@h:1") == "***@h:1"
    with pytest.raises(InputError) as caught:
        check_scheduler("tls://user:pa55@10.0.0.5:8786")
    assert "pa55" not in str(caught.value)
