"""The package and the command line agree: `sticky run --json` and
`sticky events --json` on random scenes, value for value."""

import json
import random
import subprocess
from fractions import Fraction as F

import sticky
from conftest import random_scene, scene_toml


def run_cli(binary, *args):
    out = subprocess.run([binary, *args], check=True, capture_output=True, text=True).stdout
    return [json.loads(line) for line in out.splitlines() if line.strip()]


def test_run_json_on_random_scenes(sticky_bin, tmp_path):
    rng = random.Random(27)
    for k in range(25):
        x, u, r = random_scene(rng)
        path = tmp_path / f"s{k}.toml"
        path.write_text(scene_toml(x, u, r))
        times = ["0", "1/3", "1", "5/2", "10"]
        cli = run_cli(sticky_bin, "run", str(path), *[a for t in times for a in ("--at", t)], "--json")
        scene = sticky.Scene(x, u, r)
        for t, want in zip(times, cli):
            s = scene.state(t)
            assert s.to_dict() == want
            assert s.exact_positions() == [F(v) for v in want["positions"]]
            assert list(s.positions) == [float(F(v)) for v in want["positions"]]
        # The same scene loaded from its file answers the same.
        assert sticky.Scene.load(path).state("5/2").to_dict() == cli[3]


def test_events_json_on_random_scenes(sticky_bin, tmp_path):
    rng = random.Random(2027)
    for k in range(25):
        x, u, r = random_scene(rng)
        path = tmp_path / f"e{k}.toml"
        path.write_text(scene_toml(x, u, r))
        (cli,) = run_cli(sticky_bin, "events", str(path), "--json")
        assert [e.to_dict() for e in sticky.Scene(x, u, r).events()] == cli["events"]


def test_explain_is_the_cli_explain(sticky_bin, tmp_path):
    """`Scene.explain()` is the line `sticky run --explain` prints on stderr:
    the same Solver chooses the engine for both."""
    rng = random.Random(37)
    # A hostile scene too (velocities (-1)^i/(i+1): the cost model leaves
    # the kernel for the blockwise projection).
    n = 300
    hostile = ([3 * i for i in range(n)], [F((-1) ** i, i + 1) for i in range(n)], F(1, 2))
    scenes = [random_scene(rng) for _ in range(8)] + [hostile]
    for k, (x, u, r) in enumerate(scenes):
        path = tmp_path / f"x{k}.toml"
        path.write_text(scene_toml(x, u, r))
        done = subprocess.run(
            [sticky_bin, "run", str(path), "--at", "1", "--explain"],
            check=True, capture_output=True, text=True,
        )
        text = done.stderr.strip()
        line = text.splitlines()[0]
        assert line.startswith("engine: streaming (") or line.endswith("(chosen by the cost model)"), line
        # The same file: the same text, its memory projection included.
        assert sticky.Scene.load(path).explain() == text
        # The same data in memory: the same engine line (no file, no
        # memory line).
        assert sticky.Scene(x, u, r).explain() == line
    assert "engine: blockwise" in line
