"""Real signals to the real entry point: exit 130 (SIGINT) or 143 (SIGTERM), one line, no
traceback (no SystemError out of the numba kernel), and no partial output or staging folder."""

from __future__ import annotations

import contextlib
import importlib
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

pytestmark = pytest.mark.skipif(
    not Path("/proc/self/status").exists(), reason="needs Linux /proc to see installed handlers"
)


def _handlers_installed(pid: int) -> bool:
    """True once the process catches SIGTERM (sloshkit's handler, installed just before work)."""
    try:
        status = Path(f"/proc/{pid}/status").read_text()
    except OSError:
        return False
    caught = next(line for line in status.splitlines() if line.startswith("SigCgt:"))
    return bool(int(caught.split()[1], 16) & (1 << (signal.SIGTERM - 1)))


def _interrupt(args: list[str], folder: Path, signum: int, delay_s: float) -> tuple[int, str]:
    """Start ``sloshkit ARGS`` in ``folder``, send ``signum`` ``delay_s`` after its handlers are
    installed, and return (exit code, stderr)."""
    process = subprocess.Popen(
        [sys.executable, "-c", "from sloshkit.cli import main; main()", *args],
        cwd=folder,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env={**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)},
    )
    deadline = time.monotonic() + 120.0
    while not _handlers_installed(process.pid):
        assert process.poll() is None, process.communicate()
        assert time.monotonic() < deadline
        time.sleep(0.05)
    time.sleep(delay_s)
    assert process.poll() is None, "finished before the signal: make the job larger"
    process.send_signal(signum)
    _, stderr = process.communicate(timeout=120)
    return process.returncode, stderr


def _assert_clean(folder: Path, code: int, expected: int, stderr: str) -> None:
    assert code == expected, stderr
    assert "Traceback" not in stderr and "SystemError" not in stderr, stderr
    assert [line for line in stderr.splitlines() if line.startswith("error:")] == [
        f"error: interrupted (exit {expected}); no partial output was written"
    ], stderr
    assert sorted(p.name for p in folder.iterdir()) == [], "partial output left behind"


def test_sigint_during_a_sweep_stops_between_chunks(tmp_path: Path) -> None:
    args = ["sweep", "--fill-height", "10mm:60mm:300", "--duration", "0.5s:3s:400", "--out", "maps"]
    code, stderr = _interrupt(args, tmp_path, signal.SIGINT, 1.5)
    _assert_clean(tmp_path, code, 130, stderr)


def test_sigterm_during_reproduce_removes_the_staging_folder(tmp_path: Path) -> None:
    code, stderr = _interrupt(["reproduce", "--out", "report"], tmp_path, signal.SIGTERM, 2.0)
    _assert_clean(tmp_path, code, 143, stderr)


def test_sigterm_during_plan_writes_no_trajectory(tmp_path: Path) -> None:
    args = [
        "plan",
        "--vmax", "1.5m/s", "--amax", "20m/s^2", "--jmax", "500m/s^3",
        "--max-angle", "5deg", "--max-residual", "0.25deg", "--robust", "20%",
        "--out", "trajectory.csv", "--plot", "plan.png",
    ]  # fmt: skip
    # --robust: a few seconds of work (the plain 1-D plan now takes under one)
    code, stderr = _interrupt(args, tmp_path, signal.SIGTERM, 0.5)
    _assert_clean(tmp_path, code, 143, stderr)


def test_a_command_that_reports_its_own_interruption_gets_no_second_line(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    """The CFD runner's pattern: catch the interrupt, stop its tools, print how to resume, exit
    128 + N; the entry point must not add a second line (in-process, a real SIGINT)."""
    import typer

    app_module = importlib.import_module("sloshkit.cli.app")
    from sloshkit.cli import signals

    tiny = typer.Typer()

    @tiny.command()
    def work() -> None:
        try:
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(5.0)
        except KeyboardInterrupt:
            signals.reported()
            print("interrupted at t = 0.1 s; continue with --resume", file=sys.stderr)
            raise typer.Exit(130) from None

    @tiny.callback()
    def root() -> None:
        """Two commands' worth of group so 'work' is a subcommand."""

    monkeypatch.setattr(app_module, "app", tiny)
    assert app_module.run(["work"]) == 130
    lines = [line for line in capsys.readouterr().err.splitlines() if line.strip()]
    assert lines == ["interrupted at t = 0.1 s; continue with --resume"]
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


def test_an_unreported_interruption_is_one_error_line(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    import typer

    app_module = importlib.import_module("sloshkit.cli.app")

    tiny = typer.Typer()

    @tiny.command()
    def work() -> None:
        os.kill(os.getpid(), signal.SIGTERM)
        time.sleep(5.0)

    @tiny.callback()
    def root() -> None:
        """Group."""

    monkeypatch.setattr(app_module, "app", tiny)
    assert app_module.run(["work"]) == 143
    lines = [line for line in capsys.readouterr().err.splitlines() if line.strip()]
    assert lines == ["error: interrupted (exit 143); no partial output was written"]


@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM])
def test_a_signal_after_the_command_finished_does_not_undo_it(signum):
    """A signal in the last moments of the process (the command done, the interpreter shutting
    down) leaves the command's exit code: Python would otherwise die of an uncaught Ctrl-C
    (exit -2), as a CI run once saw when a CFD test's signal came just after the run ended."""
    script = (
        "import os, sys\n"
        "from sloshkit.cli.app import run\n"
        "code = run(['--version'], exiting=True)\n"
        f"os.kill(os.getpid(), {int(signum)})\n"
        "sys.exit(code)\n"
    )
    finished = subprocess.run(
        [sys.executable, "-c", script],
        capture_output=True,
        text=True,
        env={**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)},
        timeout=120,
    )
    assert finished.returncode == 0, finished.stderr
    assert "Traceback" not in finished.stderr


def _pose_file(folder: Path, duration_s: float = 20.0) -> Path:
    """A long 3-D move (a slow circle with a tilt) for the interruption tests."""
    import numpy as np

    t = np.arange(0.0, duration_s, 0.001)
    phase = 2.0 * np.pi * t / duration_s
    half = 0.5 * np.radians(10.0) * np.sin(phase)
    rows = np.column_stack(
        [t, 0.1 * np.sin(phase), 0.1 * (1 - np.cos(phase)), 0 * t, np.sin(half), 0 * t, 0 * t,
         np.cos(half)]
    )  # fmt: skip
    folder.mkdir(exist_ok=True)
    path = folder / "move.csv"
    np.savetxt(path, rows, delimiter=",", header="t,x,y,z,qx,qy,qz,qw", comments="", fmt="%.9g")
    return path


def test_sigterm_during_a_pose_simulation_writes_no_csv_or_figure(tmp_path: Path) -> None:
    poses = _pose_file(tmp_path / "in", 80.0)
    out = tmp_path / "run"
    out.mkdir()
    args = [
        "simulate", "--pose-file", str(poses), "--model", "nonlinear",
        "--csv", "slosh.csv", "--plot", "slosh.png",
    ]  # fmt: skip
    code, stderr = _interrupt(args, out, signal.SIGTERM, 1.0)
    _assert_clean(out, code, 143, stderr)


def test_sigint_during_a_path_plan_writes_no_poses(tmp_path: Path) -> None:
    waypoints = tmp_path / "in" / "path.csv"
    waypoints.parent.mkdir()
    waypoints.write_text("x [mm],y [mm],z [mm]\n0,0,0\n300,0,0\n300,200,50\n0,200,50\n")
    out = tmp_path / "run"
    out.mkdir()
    args = [
        "plan", "--path", str(waypoints),
        "--vmax", "1.5m/s", "--amax", "8m/s^2", "--jmax", "80m/s^3",
        "--max-slosh-height", "10mm", "--max-residual-height", "2mm",
        "--out", "poses.csv", "--plot", "plan.png",
    ]  # fmt: skip
    code, stderr = _interrupt(args, out, signal.SIGINT, 0.5)
    _assert_clean(out, code, 130, stderr)


def test_sigterm_during_a_joint_export_leaves_no_file(tmp_path: Path) -> None:
    import numpy as np

    t = np.arange(0.0, 2.0 + 1e-9, 0.004)
    u = t / 2.0
    columns = np.column_stack(
        [t, 0.2 * (10 * u**3 - 15 * u**4 + 6 * u**5), 0.1 * (30 * u**2 - 60 * u**3 + 30 * u**4),
         0.05 * (60 * u - 180 * u**2 + 120 * u**3)]
    )  # fmt: skip
    plan = tmp_path / "in" / "plan.csv"
    plan.parent.mkdir()
    header = "t_s,position_m,velocity_m_s,acceleration_m_s2"
    np.savetxt(plan, columns, delimiter=",", header=header, comments="", fmt="%.10g")
    out = tmp_path / "run"
    out.mkdir()
    args = [
        "export", str(plan), "--format", "joint-csv", "--out", "joints.csv",
        "--base-pose=-0.5m,-0.13m,0.39m", "--sample-period", "1ms", "--radius", "20.5mm",
    ]  # fmt: skip
    code, stderr = _interrupt(args, out, signal.SIGTERM, 0.3)
    _assert_clean(out, code, 143, stderr)


def test_a_signal_inside_an_unraisable_callback_is_raised_again_at_a_safe_point():
    """A signal landing in a weakref callback (seen in CI inside importlib's module-lock
    callback) is not printed as "Exception ignored ... Traceback": it is delivered again and
    stops the command at the next safe point."""
    import gc
    import weakref

    from sloshkit.cli import signals

    class Owner:
        pass

    def callback(_reference: object) -> None:
        raise signals.Interrupted(signal.SIGTERM)

    with signals.installed(), pytest.raises(signals.Interrupted) as stopped:
        owner = Owner()
        reference = weakref.ref(owner, callback)
        del owner
        gc.collect()
        for _ in range(1000):  # the re-delivered signal is raised between bytecodes
            time.sleep(0.001)
    assert stopped.value.signum == signal.SIGTERM
    assert reference() is None


def test_a_finalizer_failing_after_an_interruption_is_not_printed(monkeypatch):
    """A CI run failed on "Exception ignored in: <function ObjectRef.__del__ ...>" after a
    SIGINT landed while numba was compiling: once a signal has been received, finalizers of
    the objects it tore down fail quietly; before it, they are reported as usual."""
    import gc

    from sloshkit.cli import signals

    reported: list[BaseException] = []
    monkeypatch.setattr(sys, "unraisablehook", lambda u: reported.append(u.exc_value))

    class Broken:
        def __del__(self) -> None:
            raise AttributeError("no attribute '_as_parameter_'")

    with signals.installed():
        Broken()
        gc.collect()
        assert len(reported) == 1
        with pytest.raises(signals.Interrupted):
            os.kill(os.getpid(), signal.SIGTERM)
            for _ in range(1000):
                time.sleep(0.001)
        Broken()
        gc.collect()
    assert len(reported) == 1


def test_a_signal_outside_a_commands_own_handling_still_gets_its_advice(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    """`cfd run` says how to resume wherever the signal lands: also after its own handling has
    ended (CI once saw a SIGINT on the way out of a finished run reported as "no partial output
    was written", without the resume hint)."""
    import typer

    app_module = importlib.import_module("sloshkit.cli.app")
    from sloshkit.cli import signals

    tiny = typer.Typer()

    @tiny.command()
    def work() -> None:
        signals.set_hint("continue with: sloshkit cfd run --case c --resume")
        os.kill(os.getpid(), signal.SIGINT)  # lands outside any handling of the command's own
        time.sleep(5.0)

    @tiny.callback()
    def root() -> None:
        """Group."""

    monkeypatch.setattr(app_module, "app", tiny)
    assert app_module.run(["work"]) == 130
    lines = [line for line in capsys.readouterr().err.splitlines() if line.strip()]
    assert lines == [
        "error: interrupted (exit 130); continue with: sloshkit cfd run --case c --resume"
    ]
    assert signals.hint() is None  # nothing leaks to the next command


@pytest.mark.parametrize(("signum", "code"), [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_a_signal_while_the_command_is_imported_is_one_line(signum, code, tmp_path):
    """Ctrl-C or SIGTERM during start-up (here: while the command's module is imported) ends
    the process with its code and the one interruption line: no KeyboardInterrupt traceback
    out of an import, no silent death."""
    program = (
        "import importlib, os, sys\n"
        "real = importlib.import_module\n"
        "def importing(name, *args):\n"
        "    if name == 'sloshkit.cli.model':\n"
        f"        os.kill(os.getpid(), {int(signum)})\n"
        "    return real(name, *args)\n"
        "importlib.import_module = importing\n"
        "sys.argv = ['sloshkit', 'model', '--json']\n"
        "from sloshkit.entry import main\n"
        "main()\n"
    )
    result = subprocess.run(
        [sys.executable, "-c", program], cwd=tmp_path, capture_output=True, text=True, timeout=120
    )
    assert result.returncode == code, result.stderr
    assert result.stderr == f"error: interrupted (exit {code}); no partial output was written\n"
    assert result.stdout == ""
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("writer", ["all_or_nothing", "staged_folder"])
def test_a_signal_a_library_swallowed_still_leaves_no_output(tmp_path: Path, writer: str) -> None:
    """A library that catches the interruption and carries on (``except BaseException``) must
    not let the command keep its outputs: the CLI's writers check for a received signal before
    keeping anything (``before_keeping=signals.check``), and a file that existed is restored."""
    from sloshkit.cli import signals
    from sloshkit.io.outputs import all_or_nothing, staged_folder

    kept = tmp_path / "kept.csv"
    kept.write_text("the user's\n")
    folder = tmp_path / "out"
    with signals.installed(), pytest.raises(signals.Interrupted) as stop:
        if writer == "all_or_nothing":
            block = all_or_nothing(kept, tmp_path / "new.csv", before_keeping=signals.check)
        else:
            block = staged_folder(folder, signals.check)
        with block as staging:
            target = staging if writer == "staged_folder" else tmp_path
            (target / "new.csv").write_text("complete\n")
            kept.write_text("replaced\n")
            # what a library that swallows every exception does
            with contextlib.suppress(BaseException):
                os.kill(os.getpid(), signal.SIGTERM)
    assert stop.value.exit_code == 143
    assert not (tmp_path / "new.csv").exists() and not folder.exists()
    if writer == "all_or_nothing":
        assert kept.read_text() == "the user's\n"


def test_a_signal_while_the_report_page_is_written_leaves_no_report(tmp_path: Path) -> None:
    """The report moves into its folder only after ``before_keeping`` (the CLI's
    `signals.check`): a signal recorded while the page was written (the report command runs
    inside `signals.deferred`) leaves no folder instead of a complete report and exit 130."""
    from sloshkit.cli import signals
    from sloshkit.io.scenario import parse_scenario
    from sloshkit.report.build import build_report

    scenario = parse_scenario(
        {"name": "vial", "analyses": ["model"], "container": {"radius": "20.5mm"},
         "fill": {"height": "39mm"}, "move": {"distance": "0.2m", "duration": "1s"}}
    )  # fmt: skip
    out = tmp_path / "report"

    def interrupted_meanwhile() -> None:
        os.kill(os.getpid(), signal.SIGINT)  # recorded, not raised: deferred
        signals.check()

    with signals.installed(), pytest.raises(signals.Interrupted) as stop, signals.deferred():
        build_report(scenario, out, command="test", before_keeping=interrupted_meanwhile)
    assert stop.value.exit_code == 130
    assert not out.exists() and list(tmp_path.iterdir()) == []
