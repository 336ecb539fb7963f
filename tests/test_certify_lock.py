"""``symhx.certify.arb_prec`` holds the process-wide ``ARB_LOCK`` while its block runs (issue 28):
python-flint's precision is one global setting, so Arb sections of different threads are
serialized, and the precision is restored on every exit."""

from __future__ import annotations

import threading
import time

import flint
import pytest

from symhx.certify import ARB_LOCK, arb_prec


def test_a_block_holds_the_lock_until_it_ends():
    inside = threading.Event()
    release = threading.Event()
    events: list[str] = []

    def first() -> None:
        with arb_prec(400):
            inside.set()
            release.wait(5)
            events.append(f"first done at {flint.ctx.prec}")

    def second() -> None:
        inside.wait(5)
        with arb_prec(30):
            events.append(f"second at {flint.ctx.prec}")

    t1, t2 = threading.Thread(target=first), threading.Thread(target=second)
    t1.start()
    t2.start()
    time.sleep(0.2)
    assert events == []  # the second block waits for the first
    release.set()
    t1.join()
    t2.join()
    assert events == ["first done at 400", "second at 30"]


def test_blocks_nest_and_restore_the_precision_on_errors():
    before = flint.ctx.prec
    with arb_prec(200):
        with arb_prec(90):
            assert flint.ctx.prec == 90
        assert flint.ctx.prec == 200
    with pytest.raises(ZeroDivisionError), arb_prec(300):
        1 / 0  # noqa: B018
    assert flint.ctx.prec == before
    assert ARB_LOCK.acquire(blocking=False)  # not left held
    ARB_LOCK.release()


def test_arb_prec_sets_the_series_length_for_the_block_only():
    """flint truncates power series at ``ctx.cap`` terms (10 by default, silently): a block
    that asks for 30 coefficients gets them, and the length is restored after it."""
    from flint import arb_series

    before = flint.ctx.cap
    with arb_prec(128, cap=31):
        assert len(arb_series([1, 1], prec=31).exp().coeffs()) == 31
    assert flint.ctx.cap == before
    with arb_prec(128):
        assert flint.ctx.cap == before
