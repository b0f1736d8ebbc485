"""Printing the deck waits for its demos as long as they keep drawing, and names a stall."""

from __future__ import annotations

import pytest

from lab.web import slides


class FakePage:
    """A page whose demos finish one per `every` polls; None in a schedule never finishes."""

    def __init__(self, finish_at: list[int | None]):
        self.finish_at = finish_at
        self.polls = 0

    def evaluate(self, _js: str) -> list[bool]:
        self.polls += 1
        return [at is not None and self.polls >= at for at in self.finish_at]

    def wait_for_timeout(self, _ms: float) -> None:
        pass


def test_slow_demos_that_keep_finishing_are_waited_for(monkeypatch):
    clock = iter(range(0, 10_000, 10))  # each poll takes 10 s of a very busy machine
    monkeypatch.setattr(slides.time, "monotonic", lambda: next(clock))
    page = FakePage([5, 12, 20, 28])  # 280 s in all, never 120 s without one finishing
    slides._wait_for_first_pictures(page, slides.DEMOS_RENDERED, stall_s=120)
    assert page.polls == 28


def test_a_demo_that_never_draws_is_named(monkeypatch):
    clock = iter(range(0, 10_000, 10))
    monkeypatch.setattr(slides.time, "monotonic", lambda: next(clock))
    page = FakePage([2, None, 3])
    with pytest.raises(slides.SlidesError, match=r"demo\(s\) 2 of 3 drew nothing for 120 s"):
        slides._wait_for_first_pictures(page, slides.DEMOS_RENDERED, stall_s=120)
