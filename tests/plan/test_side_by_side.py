"""Two searches at once (`sloshkit.plan.path.side_by_side`)."""

from __future__ import annotations

import threading
import time

import pytest

from sloshkit.plan.path.side_by_side import Abandoned, side_by_side


def test_the_background_runs_in_another_thread_and_its_result_is_returned() -> None:
    seen: dict[str, object] = {}

    def background(log):
        seen["thread"] = threading.get_ident()
        log("working")
        return 42

    def foreground(job):
        seen["result in front"] = job.result()

    lines: list[str] = []
    assert side_by_side(background, foreground, lines.append, "upright: ") == 42
    assert seen["thread"] != threading.get_ident()
    assert seen["result in front"] == 42
    assert lines == ["upright: working"]


def test_a_failure_in_front_stops_the_background_at_its_next_line() -> None:
    stopped = threading.Event()
    programs = []

    def background(log):
        try:
            for _ in range(1000):
                log("program")
                programs.append(1)
                time.sleep(0.01)
        except Abandoned:
            stopped.set()
            raise
        return "finished"

    def foreground(job):
        raise KeyboardInterrupt  # a signal in front, as the CLI's Interrupted

    with pytest.raises(KeyboardInterrupt):
        side_by_side(background, foreground, None, "")
    assert stopped.is_set()
    assert len(programs) < 1000


def test_a_failure_in_the_background_reaches_the_caller() -> None:
    def background(log):
        raise RuntimeError("no duration met the limits")

    with pytest.raises(RuntimeError, match="no duration"):
        side_by_side(background, lambda job: None, None, "")
