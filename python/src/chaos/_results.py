"""Result objects: small frozen views of a command's JSON object.

Each attribute is a key of the command's ``--json`` output; lists of numbers become read-only NumPy
arrays (``None``, the JSON's "no value", becomes NaN), lists of equal-length lists become 2-D arrays,
nested objects become read-only mappings. ``to_dict()`` returns the JSON object itself, exactly as
``json.loads`` of the command's output gives it.
"""
import copy
import keyword
import numbers
import types

import numpy as np


def _is_number(v):
    return v is None or (isinstance(v, numbers.Real) and not isinstance(v, bool))


def _array(values, dtype):
    a = np.array([np.nan if v is None else v for v in values], dtype=dtype)
    a.flags.writeable = False
    return a


def _convert(value):
    if isinstance(value, dict):
        return types.MappingProxyType({k: _convert(v) for k, v in value.items()})
    if not isinstance(value, list):
        return value
    if not value:
        return _array([], float)
    if all(isinstance(v, bool) for v in value):
        return _array(value, bool)
    if all(_is_number(v) for v in value):
        exact = all(isinstance(v, numbers.Integral) for v in value)
        return _array(value, np.int64 if exact else float)
    rows = [v for v in value if v is not None]
    if rows and all(isinstance(r, list) and all(_is_number(x) for x in r) for r in rows) \
            and len({len(r) for r in rows}) == 1:
        width = len(rows[0])
        a = np.array([[np.nan] * width if r is None else [np.nan if x is None else x for x in r] for r in value],
                     dtype=float)
        a.flags.writeable = False
        return a
    return tuple(_convert(v) for v in value)


class Result:
    """The result of one command: attributes are the keys of its ``--json`` object.

    A key that is a Python keyword (``lambda``) is also reachable with a trailing underscore
    (``r.lambda_``) and, like every key, as ``r["lambda"]``.
    """

    __slots__ = ("_json", "_values", "_arrays", "_evidence")

    def __init__(self, json, arrays=None, evidence=None):
        object.__setattr__(self, "_json", json)
        # What the command's plot draws beyond its JSON (analyze: the information curve and the local
        # slopes), kept out of the attributes and of to_dict().
        object.__setattr__(self, "_evidence", evidence or {})
        object.__setattr__(self, "_values", {})  # converted on first access
        # Values handed over as arrays (generate's components): the JSON gets them as lists on to_dict().
        object.__setattr__(self, "_arrays", arrays or {})
        for key, value in self._arrays.items():
            self._values[key] = value

    def __getitem__(self, key):
        values = self._values
        if key not in values:
            values[key] = _convert(self._json[key])
        return values[key]

    def __getattr__(self, name):
        json = object.__getattribute__(self, "_json")
        if name in json or name in object.__getattribute__(self, "_arrays"):
            return self[name]
        if name.endswith("_") and keyword.iskeyword(name[:-1]) and name[:-1] in json:
            return self[name[:-1]]
        raise AttributeError(f"{type(self).__name__} has no attribute {name!r} (keys: {', '.join(json)})")

    def __setattr__(self, name, value):
        raise AttributeError(f"{type(self).__name__} is frozen")

    def __delattr__(self, name):
        raise AttributeError(f"{type(self).__name__} is frozen")

    def __dir__(self):
        return sorted(set(super().__dir__()) | {k if not keyword.iskeyword(k) else k + "_" for k in self._json})

    def keys(self):
        return list(self._json) + [k for k in self._arrays if k not in self._json]

    def to_dict(self):
        """The command's JSON object (a fresh copy): equal to ``json.loads`` of ``chaos <command> --json``."""
        out = copy.deepcopy(self._json)
        for key, value in self._arrays.items():
            out[key] = {k: v.tolist() for k, v in value.items()} if isinstance(value, types.MappingProxyType) \
                else value.tolist()
        return out

    def __eq__(self, other):
        return type(self) is type(other) and self._json == other._json

    __hash__ = None

    def __repr__(self):
        shown = []
        for key in ("status", "d2", "lambda", "first_minimum", "embedding_dimension", "delay", "decorrelation_time"):
            if key in self._json and not isinstance(self._json[key], (list, dict)):
                shown.append(f"{key}={self._json[key]!r}")
        for key in ("estimate", "d2_estimate", "lambda_1"):
            answer = self._json.get(key)
            if isinstance(answer, dict):
                shown.append(f"{key}={answer.get('value')!r} ({answer.get('status')})")
        return f"<{type(self).__name__} {self._json.get('command', '')}: {', '.join(shown)}>"

    def plot(self, ax=None):
        """Draws the command's figure with matplotlib; returns the axes."""
        from . import _plot
        draw = getattr(_plot, self._json["command"], None)
        if draw is None:
            raise TypeError(f"chaos {self._json['command']} has no figure")
        return draw(self, ax)


def make(json, arrays=None, evidence=None):
    name = "".join(part.capitalize() for part in json["command"].replace("-", "_").split("_")) + "Result"
    cls = _classes.get(name)
    if cls is None:
        cls = _classes[name] = type(name, (Result,), {"__slots__": ()})
    return cls(json, arrays, evidence)


_classes = {}
