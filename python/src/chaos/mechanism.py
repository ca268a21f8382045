"""The clearance-joint slider-crank simulator (the ``mechanism`` command) on NumPy arrays.

    from chaos import mechanism
    scene = mechanism.default_scene()                  # the seed's scene (``mechanism scene --default``)
    scene.set("joint.slider.clearance", 3e-4)          # any scene key, validated at once
    run = mechanism.simulate(scene, stroboscopic=True)
    run.summary                                        # == ``mechanism simulate --json`` (wall_seconds apart)
    run.signals["slider_y"], run.stroboscopic["slider_y"]

The module is ``chaos.mechanism``, not a top-level ``mechanism``: that name belongs to an unrelated
package on PyPI (kinematics of mechanisms and cams). docs/reference/mechanism/ describes the model, the scene
keys and the signals.
"""
import os
import types

import numpy as np

from . import _core

__all__ = ["Scene", "default_scene", "load_scene", "simulate", "Simulation"]


def _toml_value(value):
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        value = float(value)
        if not np.isfinite(value):
            raise ValueError(f"scene values must be finite (got {value})")
        return repr(value)
    if isinstance(value, str):
        return '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    raise TypeError(f"a scene value is a number, a bool or a string (got {type(value).__name__})")


class Scene:
    """A scene: TOML text (empty: the built-in seed scene) and the keys set on it, in order, resolved by
    the library's reader exactly as ``mechanism simulate [scene.toml] --set key=value ...`` resolves them."""

    def __init__(self, toml="", source="scene", overrides=()):
        self._toml, self._source, self._overrides = toml, source, list(overrides)
        _core.scene_toml(self._toml, self._overrides, self._source)  # refuses an invalid scene now

    def set(self, key, value):
        """Sets a dotted scene key ("joint.slider.clearance", "run.duration", "integrator.method", ...).
        Raises ValueError with the library's message for an unknown key, a wrong type or an impossible
        value; the scene is then unchanged. Returns the scene."""
        setting = f"{key}={_toml_value(value)}"
        _core.scene_toml(self._toml, self._overrides + [setting], self._source)
        self._overrides.append(setting)
        return self

    def copy(self):
        return Scene(self._toml, self._source, self._overrides)

    @property
    def overrides(self):
        """The settings made with set(), as the command's --set arguments."""
        return tuple(self._overrides)

    def to_toml(self):
        """The resolved scene, every key with its value (``mechanism scene ... --set ...``)."""
        return _core.scene_toml(self._toml, self._overrides, self._source)

    def warnings(self):
        """What a valid scene still deserves to be told (the command prints these on stderr)."""
        return list(_core.scene_warnings(self._toml, self._overrides, self._source))

    def __repr__(self):
        return f"<Scene {self._source}{''.join(' --set ' + o for o in self._overrides)}>"


def default_scene():
    """The seed's scene, built in (``mechanism scene --default`` prints it with a comment on every key)."""
    return Scene()


def load_scene(path):
    """A scene from a TOML file (keys not in the file keep the seed scene's values)."""
    path = os.fspath(path)
    if os.path.isdir(path):
        raise ValueError(f"scene = {path}: is a directory, not a scene file")
    try:
        with open(path, encoding="utf-8") as f:
            text = f.read()
    except OSError as error:
        raise ValueError(f"scene = {path}: cannot be opened (missing or unreadable file)") from error
    return Scene(text, path)


class Simulation:
    """One run: ``summary`` (the command's --json object), its keys as attributes (``status``,
    ``end_time``, ``steps``, ``max_penetration``, ...), ``signals`` and ``stroboscopic`` (read-only
    arrays by signal name; ``stroboscopic["revolution"]`` numbers the revolutions), ``units``."""

    def __init__(self, raw):
        self.summary = raw["summary"]
        names = list(raw["names"])
        self.units = types.MappingProxyType(dict(zip(names, raw["units"])))
        series, strobe = raw["series"], raw["stroboscopic"]
        series.flags.writeable = False
        strobe.flags.writeable = False
        self.signals = types.MappingProxyType({n: series[k] for k, n in enumerate(names)})
        columns = {"revolution": raw["revolution"].astype(np.int64)} if raw["stroboscopic_run"] else {}
        if raw["stroboscopic_run"]:
            columns.update({n: strobe[k] for k, n in enumerate(names)})
        self.stroboscopic = types.MappingProxyType(columns)

    def __getattr__(self, name):
        summary = self.__dict__.get("summary", {})
        if name in summary:
            return summary[name]
        raise AttributeError(name)

    def to_dict(self):
        """The summary, as ``mechanism simulate --json`` writes it."""
        return dict(self.summary)

    def plot(self, ax=None):
        """The slider's transverse position against the crank angle (seed Fig. 3), the stroboscopic
        samples marked when there are any."""
        import matplotlib.pyplot as plt
        if ax is None:
            ax = plt.subplots()[1]
        angle = np.degrees(self.signals["crank_angle"]) % 360.0
        ax.plot(angle, self.signals["slider_y"], ",", label="time series")
        if self.stroboscopic:
            ax.plot(np.degrees(self.stroboscopic["crank_angle"]) % 360.0, self.stroboscopic["slider_y"], "o",
                    ms=3, label="stroboscopic")
        ax.set_xlabel("crank angle (degrees)")
        ax.set_ylabel(f"slider_y ({self.units['slider_y']})")
        ax.set_title(f"slider trajectory: {self.status}")
        ax.legend()
        return ax

    def __repr__(self):
        return (f"<Simulation {self.summary['status']}: t = {self.summary['end_time']} s, "
                f"{self.summary['samples']} samples, {self.summary['stroboscopic_samples']} stroboscopic>")


def simulate(scene=None, *, stroboscopic=None, progress=None):
    """Integrates the scene (the seed's when None) as ``mechanism simulate`` does, with the GIL released;
    ``stroboscopic=True`` also samples once per crank revolution (``--stroboscopic``). A run that cannot
    continue ends with a ``status`` and a ``message``, as the command's summary says; it raises nothing.
    Ctrl-C stops it within about a percent of the simulated time. ``progress``: a callable taking the
    fraction done."""
    scene = default_scene() if scene is None else scene
    if not isinstance(scene, Scene):
        raise TypeError(f"simulate takes a Scene (got {type(scene).__name__})")
    return Simulation(_core.simulate(scene._toml, scene._overrides, scene._source, stroboscopic, progress))
