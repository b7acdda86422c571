# The README's Python simulation examples (section "Python"), run as
# written: the friction sweep, and the Gymnasium-style environment on
# ANYmal C (../shared/corpus; skipped where it is absent).
import re

import numpy as np
import pytest

from conftest import ROOT
from test_sim_robot import ANYMAL, ANYMAL_Q, GROUND


def readme_block(marker):
    blocks = re.findall(r"```python\n(.*?)```", (ROOT / "README.md").read_text(), re.S)
    found = [b for b in blocks if marker in b]
    assert len(found) == 1, marker
    return found[0]


def test_friction_sweep():
    names = {}
    exec(readme_block("RAMP = "), names)
    slid, frictions = names["slid"], names["frictions"]
    assert slid.shape == (6,)
    # a = g (sin 20 - mu cos 20): 1.22 m in 1 s at mu 0.1; none past tan 20.
    expected = np.maximum(0, 9.81 * (np.sin(np.radians(20)) - frictions * np.cos(np.radians(20)))) / 2
    assert slid[:2] == pytest.approx(expected[:2], rel=0.02)
    assert slid[2] == pytest.approx(expected[2], rel=0.1)  # 5% short, nearer the sticking limit
    assert np.all(slid[3:] < 1e-3)


def test_gymnasium_style_loop(tmp_path, monkeypatch):
    if not ANYMAL.exists():
        pytest.skip("../shared/corpus/robots/anymal_c is absent")
    (tmp_path / "anymal.rscene").write_text(
        "raisim_engine_scene 1\ntime_step 0.0025\ngravity 0 0 -9.81\n" + GROUND +
        "articulated_resource res ANYmal %s\narticulated /World/Anymal res 0 0 0.54 1 0 0 0 true true "
        "generalizedCoordinate=%s\n" % (ANYMAL, ",".join(map(str, ANYMAL_Q))))
    monkeypatch.chdir(tmp_path)
    import rscene
    names = {"np": np, "rscene": rscene}
    exec(readme_block("class Stand"), names)
    env = names["env"]
    assert env.sim.steps == 4000
    obs = names["obs"]
    assert obs.shape == (17 + 18,) and np.all(np.isfinite(obs))
    assert 0.45 < env.robot.q[2] < 0.56  # standing
