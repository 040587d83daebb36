"""Value behaviour of the native classes: equality of scenes, pickling and
deep copies of Scene, State, States and CompareReport, and ``dir()`` of a report
listing its figures."""

from . import _sticky  # type: ignore[attr-defined]  # the native module has no stub of its own


def _scene(radius, positions, velocities):
    """A scene rebuilt from its exact data (pickling)."""
    return _sticky.Scene(positions, velocities, radius)


def scene_reduce(scene):
    return (_scene, (scene.radius, scene.exact_positions(), scene.exact_velocities()))


def scene_eq(a, b):
    """Scenes are equal when their data are: the same radius, positions and
    velocities, exactly (name and kind aside)."""
    if not isinstance(b, _sticky.Scene):
        return NotImplemented
    return a is b or (
        a.n == b.n
        and a.radius == b.radius
        and a.exact_positions() == b.exact_positions()
        and a.exact_velocities() == b.exact_velocities()
    )


def scene_hash(scene):
    return hash((scene.n, scene.radius))


def _state(scene, t):
    """A state computed again (pickling)."""
    return scene.state(t)


def state_reduce(state):
    return (_state, (state.scene, state.t))


def states_again(scene, times):
    """The states of a scene at these times again, none computed (pickling)."""
    return scene.states(times)


def report_dir(report):
    """The report's attributes, and with one time its frame's figures."""
    names = set(object.__dir__(report))
    if len(report.frames) == 1:
        names |= {n for n in dir(_sticky.CompareFrame) if not n.startswith("_")}
    return sorted(names)


def report_again(scene, t, positions, velocities, multipliers, clusters, contact_tol, overlap_tol):
    """A comparison made again from the exact answer compared (pickling)."""
    return _sticky.compare(
        scene,
        t,
        positions,
        velocities,
        multipliers=multipliers,
        clusters=clusters,
        contact_tol=contact_tol,
        overlap_tol=overlap_tol,
    )
