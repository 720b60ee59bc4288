"""The server's warnings go to the request they were raised for (`web.app._warnings`), also
when two requests compute at once in two threads (a long drawing in a worker thread, a drag's
frame in the event loop), and warnings of no request go where they went before."""

from __future__ import annotations

import threading
import warnings

import pytest

from linkwork.errors import LinkworkWarning
from linkwork.web import app as web_app


def test_two_threads_collect_their_own_warnings_interleaved():
    turns = [threading.Event() for _ in range(7)]
    got: dict[str, list[str]] = {}

    def request(name: str, mine: range) -> None:
        with web_app._warnings() as out:
            for k in mine:  # A raises at turns 0, 2, 4, B at 1, 3, 5: each waits for the other
                turns[k].wait(5)
                warnings.warn(f"{name} {k}", LinkworkWarning)
                warnings.warn(f"{name} {k}", LinkworkWarning)  # the same twice: kept once
                turns[k + 1].set()
        got[name] = out

    a = threading.Thread(target=request, args=("A", range(0, 6, 2)))
    b = threading.Thread(target=request, args=("B", range(1, 6, 2)))
    a.start(), b.start()
    turns[0].set()
    a.join(10), b.join(10)
    assert got == {"A": ["A 0", "A 2", "A 4"], "B": ["B 1", "B 3", "B 5"]}


def test_a_warning_of_no_request_is_shown_as_before():
    with web_app._warnings() as out:
        warnings.warn("inside", LinkworkWarning)
    with pytest.warns(LinkworkWarning, match="outside"):
        warnings.warn("outside", LinkworkWarning)
    with pytest.warns(UserWarning, match="not ours"), web_app._warnings() as inner:
        warnings.warn("not ours", UserWarning)  # only LinkworkWarnings are collected
    assert out == ["inside"] and inner == []


def test_nested_requests_keep_their_own_lists():
    with web_app._warnings() as outer:
        warnings.warn("first", LinkworkWarning)
        with web_app._warnings() as inner:
            warnings.warn("second", LinkworkWarning)
        warnings.warn("third", LinkworkWarning)
    assert outer == ["first", "third"] and inner == ["second"]
