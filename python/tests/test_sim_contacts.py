# rscene.Simulation.contacts() (issue 28): the rigid contact points after
# each step, as numpy arrays; and a long step() that Ctrl-C interrupts,
# leaving the simulation consistent.
import _thread
import signal
import threading
import time

import numpy as np
import pytest

import rscene
from test_simulation import DROP


def test_no_contacts_before_the_first_step():
    sim = rscene.Simulation(rscene.loads(DROP.format(z=0.1)))
    c = sim.contacts()
    assert len(c) == 0 and c.position.shape == (0, 3) and c.normal.shape == (0, 3) and c.depth.shape == (0,)


def test_a_resting_box_carries_its_weight():
    sim = rscene.Simulation(rscene.loads(DROP.format(z=1)))
    sim.step(1500)
    c = sim.contacts()
    assert len(c) == sim.contact_count == 4  # the box's four corners
    assert c.position.dtype == np.float64 and c.position.shape == (4, 3)
    pairs = set(zip(c.body_a, c.body_b))
    assert pairs == {("/World/Box", "/World/Ground")}
    assert c.link_a == ["", "", "", ""] and c.link_b == ["", "", "", ""]
    # Points on the ground (B) at the corners; the ground's normal points
    # up, toward the box; the impulses carry 1 kg against gravity.
    assert np.allclose(c.position[:, 2], 0, atol=1e-6)
    assert np.allclose(np.abs(c.position[:, :2]), 0.1, atol=1e-4)
    assert np.allclose(c.normal, [0, 0, 1])
    assert np.all(c.depth > 0) and np.all(c.depth < 0.005)
    assert c.impulse.sum() / sim.time_step == pytest.approx(9.81, rel=0.02)
    assert c.involving("/World/Box").all() and c.involving("/World/Ground").all()


def test_contacts_index_and_iterate():
    # From a fresh-user trial: Contacts had len() but no [i] or iteration,
    # and involving() of a name that is no body gave an empty mask.
    sim = rscene.Simulation(rscene.loads(DROP.format(z=1)))
    sim.step(1500)
    c = sim.contacts()
    points = list(c)
    assert len(points) == len(c) == 4
    first = c[0]
    assert isinstance(first, rscene.Contact)
    assert (first.body_a, first.body_b, first.link_a) == ("/World/Box", "/World/Ground", "")
    assert np.array_equal(first.position, c.position[0]) and first.depth == c.depth[0]
    assert c[-1].depth == points[3].depth == c.depth[3] and c[np.int64(2)].impulse == c.impulse[2]
    with pytest.raises(IndexError):
        c[4]
    with pytest.raises(TypeError):
        c[0.5]
    with pytest.raises(KeyError, match="no body named '/nope'"):
        c.involving("/nope")
    with pytest.raises(TypeError):
        c.involving(3)


def test_a_falling_box_has_none():
    sim = rscene.Simulation(rscene.loads(DROP.format(z=5)))
    sim.step(10)
    assert len(sim.contacts()) == 0


def test_ctrl_c_interrupts_a_long_step():
    # A process started with SIGINT ignored (a shell's background job) has
    # no Ctrl-C to give: interrupt_main() then does nothing, and the step
    # below would run for years.
    if signal.getsignal(signal.SIGINT) is not signal.default_int_handler:
        pytest.skip("SIGINT is not Python's here (ignored by the parent process)")
    sim = rscene.Simulation(rscene.loads(DROP.format(z=1)))
    timer = threading.Timer(0.3, _thread.interrupt_main)
    start = time.monotonic()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            sim.step(10 ** 12)  # years
    finally:
        timer.cancel()
    assert time.monotonic() - start < 5  # it came back soon after the signal
    taken = sim.steps
    assert 0 < taken < 10 ** 12
    # Stopped between two steps: consistent, and it steps on.
    assert sim.time == pytest.approx(taken * 0.001)
    assert np.all(np.isfinite(sim.body_pose("box")))
    sim.step(5)
    assert sim.steps == taken + 5
    assert sim.body_pose("box")[2] == pytest.approx(0.1, abs=2e-3)
