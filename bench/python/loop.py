"""bench/python/loop.py SCENE STEPS - the Python side of bench/python/run.sh:
the loops of rscene-python-bench-loop (bench/python/loop.cpp) through the
rscene module, on the same scene, each from a freshly prepared simulation.
Prints "NAME CPU_SECONDS WALL_SECONDS STEPS" per loop."""
import sys
import time

import numpy as np

import rscene


def prepare(doc):
    sim = rscene.Simulation(doc)
    robot = sim.robots[0]
    q0 = robot.q
    robot.set_pd_targets(q0, 400, 10)
    return sim, robot, q0


def loop(name, doc, body):
    sim, robot, q0 = prepare(doc)
    c, w = time.process_time(), time.perf_counter()
    body(sim, robot, q0)
    c, w = time.process_time() - c, time.perf_counter() - w
    print("%s %.6f %.6f %d" % (name, c, w, sim.steps), flush=True)


def main():
    doc = rscene.load(sys.argv[1])
    steps = int(sys.argv[2])

    def step1(sim, robot, q0):
        step = sim.step
        for _ in range(steps):
            step()

    def step1000(sim, robot, q0):
        for _ in range(steps // 1000):
            sim.step(1000)

    def rl(sim, robot, q0):
        total = 0.0
        target = q0.copy()
        for i in range(steps):
            q, u = robot.state()
            total += q[2]
            target[7] = q0[7] + 0.01 * (i % 2)
            robot.set_pd_targets(target, 400, 10)
            sim.step()
        assert total > 0

    loop("step1", doc, step1)
    loop("step1000", doc, step1000)
    loop("rl", doc, rl)


main()
