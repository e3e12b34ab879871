"""billiards' flight and the bed's bounce against pooltool main's 3D engine, on the same
jump strokes: each hop's landing time and point, where the hopping ends, where the ball
stops (issue 45).

    python scripts/jump_vs_pooltool.py --pooltool-python /work/ptm-venv/bin/python
        [--strokes 2:60,3:45,4:30,2.5:70]

pooltool main (unreleased; its airborne state, `ball_table` laws and 3D stroke, read from
its repository: E. Kiefl, github.com/ekiefl/pooltool) runs in a subprocess of its own
venv, with its `sandbox/airborne_demos.py` engine (every strategy 3D, the stroke
`InstantaneousPoint3D`): a cue ball at rest at (0.5, 0.5) on its default table, struck
along +y at V0 m/s and `theta` degrees of elevation through the ball's centre.

billiards gets the velocity and spin pooltool's stroke left the ball with (the strike
laws differ: TP A-30's cue mass and tip efficiency here, pooltool's instantaneous point
there), so what is compared is the flight and the bed: the same ball (pooltool's R, m),
g, e_t and the bed's friction (pooltool's u_s), the cloth's rolling and spinning
friction as pooltool's (u_r, its u_sp), the spin model. Each row: a hop's landing
(pooltool's `ball_table` event; here the flying state's end), its time and its distance
along the shot; then when and where the ball meets the far cushion, where the
comparison stops (pooltool's cushion is its own law, not one of this project's), or
when billiards' ball leaves the table over the rail (pooltool's lands beyond it).

Prints markdown tables with the command, the date and both versions.
"""

from __future__ import annotations

import argparse
import datetime
import json
import subprocess
import sys
from typing import Any

import numpy as np

from billiards.physics.engine.setup import Setup
from billiards.physics.methods import entry

POOLTOOL = r"""
import json, sys, importlib.util
spec = importlib.util.spec_from_file_location("demos", sys.argv[1])
demos = importlib.util.module_from_spec(spec)
spec.loader.exec_module(demos)
from pooltool.evolution.event_based.simulate import simulate
from pooltool.objects.ball.datatypes import Ball
from pooltool.objects.cue.datatypes import Cue
from pooltool.objects.table.datatypes import Table
from pooltool.system.datatypes import System
out = []
for speed, theta in json.loads(sys.argv[2]):
    cue = Cue(cue_ball_id="cue")
    cue.set_state(V0=speed, phi=90.0, theta=theta, a=0.0, b=0.0)
    system = System(cue=cue, table=Table.default(), balls=(Ball.create("cue", xy=(0.5, 0.5)),))
    params = system.balls["cue"].params
    system = simulate(system, engine=demos._build_3d_engine(), inplace=False)
    events = []
    for event in system.events:
        agent = next((a for a in event.agents if a.id == "cue"), None)
        state = None if agent is None or agent.final is None else agent.final.state.rvw.tolist()
        events.append((event.event_type.value, event.time, state))
    out.append({"events": events, "R": params.R, "m": params.m, "g": params.g,
                "u_s": params.u_s, "u_r": params.u_r, "e_t": params.e_t,
                "u_sp": params.u_sp_proportionality * params.R})
print(json.dumps(out))
"""


def pooltool_runs(python: str, demos: str, strokes: list[tuple[float, float]]) -> Any:
    done = subprocess.run(
        [python, "-c", POOLTOOL, demos, json.dumps(strokes)],
        capture_output=True,
        text=True,
        check=True,
        env={"PYTHONHASHSEED": "0", "PATH": "/usr/bin:/bin"},
    )
    return json.loads(done.stdout)


def ours(run: dict[str, Any]) -> dict[str, Any]:
    """This project's spin model from pooltool's post-strike state (its first event
    after the stroke: the ball as it meets the bed)."""
    struck = next(state for kind, _, state in run["events"] if kind == "stick_ball")
    (x, y, _), (vx, vy, vz), spin = struck
    radius, g = run["R"], run["g"]
    setup = Setup.of(
        [(x, y)],
        [(vx, vy)],
        masses=[run["m"]],
        spins=[spin],
        drives=[-vz],
        model="spin",
        radius=radius,
        table_size=(0.9906, 1.9812),  # pooltool's default table, x across, y along
        gravity=g,
        table_restitution=run["e_t"],
        sliding_friction=run["u_s"],
        slide_decel=run["u_s"] * g,
        decel=run["u_r"] * g,
        spin_decel=5 * run["u_sp"] * g / (2 * radius),
        max_time=20.0,
    )
    result = next(iter(entry.run_batch([(setup, ("cue",), "event", 1 / 240)])))
    assert not isinstance(result, Exception), result
    # The ball leaves the bed at 0 (its launch is its start); each landing ends a flying
    # state: flying again, or the last, sliding or rolling.
    landings = []
    for transition in result.transitions:
        landings.append(transition.time)
        if transition.state != "flying":
            break
    cushion = next((event.time for event in result.events if event.kind == "cushion"), None)
    # Over the rail: an event of kind pocket with no pocket (billiards' own outcome).
    left = next((e.time for e in result.events if e.kind == "pocket" and e.pocket is None), None)
    times = [*landings, result.rest_time if cushion is None else cushion]
    points = result.positions_at(np.array(times))[:, 0]
    return {
        "landings": list(zip(landings, (points[:-1, 1] - y).tolist(), strict=True)),
        "cushion": None if cushion is None else (cushion, float(points[-1, 1] - y)),
        "left": left,
    }


def theirs(run: dict[str, Any]) -> dict[str, Any]:
    start = next(state for kind, _, state in run["events"] if kind == "stick_ball")[0][1]
    tables = [(t, s) for kind, t, s in run["events"] if kind == "ball_table" and t > 0]
    cushion = next(((t, s) for kind, t, s in run["events"] if "cushion" in kind), None)
    return {
        "landings": [(t, s[0][1] - start) for t, s in tables],
        "cushion": None if cushion is None else (cushion[0], cushion[1][0][1] - start),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--pooltool-python", required=True)
    parser.add_argument(
        "--demos",
        default="/work/pooltool-main/sandbox/airborne_demos.py",
        help="pooltool main's sandbox/airborne_demos.py (its 3D engine)",
    )
    parser.add_argument(
        "--strokes",
        default="2:60,3:45,4:30,2.5:70",
        help="V0 m/s : elevation degrees, comma-separated",
    )
    args = parser.parse_args()
    strokes = [
        (float(speed), float(theta))
        for speed, theta in (pair.split(":") for pair in args.strokes.split(","))
    ]
    runs = pooltool_runs(args.pooltool_python, args.demos, strokes)
    print("$ python " + " ".join(sys.argv))
    print(f"{datetime.datetime.now(datetime.UTC):%Y-%m-%d %H:%M} UTC")
    print()
    print("| stroke | hop | pooltool: lands at s | along m | billiards: lands at s | along m |")
    print("|---|---|---|---|---|---|")
    for (speed, theta), run in zip(strokes, runs, strict=True):
        mine, other = ours(run), theirs(run)
        hops = max(len(mine["landings"]), len(other["landings"]))
        for hop in range(hops):
            cells = []
            for side in (other, mine):
                landing = side["landings"][hop] if hop < len(side["landings"]) else None
                cells += (
                    ["-", "-"] if landing is None else [f"{landing[0]:.4f}", f"{landing[1]:.4f}"]
                )
            print(f"| {speed} m/s, {theta} deg | {hop + 1} | " + " | ".join(cells) + " |")
        cells = []
        for side in (other, mine):
            met = side["cushion"]
            cells += ["-", "-"] if met is None else [f"{met[0]:.4f}", f"{met[1]:.4f}"]
        print(f"| {speed} m/s, {theta} deg | the cushion | " + " | ".join(cells) + " |")
        if mine["left"] is not None:
            past = [f"{t:.4f} s at {along:.4f} m" for t, along in other["landings"]]
            print(
                f"| {speed} m/s, {theta} deg | over the rail | lands past it: {', '.join(past)} "
                f"| | leaves the table at {mine['left']:.4f} s | |"
            )


if __name__ == "__main__":
    main()
